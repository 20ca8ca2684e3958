// The pressure microphones (PressureMicrophones.h) against the air box's pressure at the same
// points: octave-band levels of the first 300 ms after a strike.
#include "MicBands.h"
#include "Report.h"

#include <catch2/catch.hpp>

using namespace snaresim;
using namespace snaresim::test;

TEST_CASE("pressure microphones: octave bands 125 Hz - 4 kHz within 3 dB of the air box's pressure, and the whole real-time drum to 500 Hz",
          "[mics][airbox][slow]")
{
    // The same heads' motion heard two ways: the air box's own pressure at the microphones and
    // the radiation model on the box's heads. The box's heads stand in for the real-time ones
    // here: the real-time drum's heads move otherwise above 500 Hz (printed below, and
    // docs/MODEL.md, "The real-time drum as a whole"), which is the reduced air's part, not the
    // microphones'.
    const DrumConfig cfg = micDrum();
    const double fs = cfg.sampleRate_Hz;
    const int samples = (int) std::lround(0.3 * fs);
    const Recording box = record(inBox(cfg), samples);
    CHECK(worstDifference("radiation model on the box's heads", box.model, box.drum, fs, kOctaves.back(), reportFile()) < 3.0);
    // The check can fail: a head's velocity under the microphone as a plane wave's pressure
    // (the microphones before the radiation model) is far from it.
    CHECK(worstDifference("rho c v under the microphone", box.plane, box.drum, fs, kOctaves.back(), reportFile()) > 6.0);

    // The whole real-time drum (cavity, outside air and its near field) beside the box. Its air's
    // kinetic reserves widen its grids by 1-5 %, and this stick chatters on the batter's grid, so
    // the box's heads are put on the same grids (a 2 % wider grid alone moves these bands by up
    // to 5 dB: airbox_figures whole-drum coarser=1.02 no-near-field).
    DrumConfig realTime = cfg;
    realTime.outside.enabled = realTime.outside.nearField = true;
    const Recording boxOnGrids = record(onGridsOf(inBox(cfg), realTime), samples);
    const Recording rt = record(realTime, samples);
    // Within 3 dB up to 500 Hz (above, the box's inside air carries sound the reduced cavity
    // does not: docs/MODEL.md, "The real-time drum as a whole")
    CHECK(worstDifference("the real-time drum (cavity, outside air, near field), the box on its grids", rt.drum, boxOnGrids.drum, fs, 500.0,
                          reportFile()) < 3.0);
    // Reported: without the near field the batter's (2,1) mode stands 14 % high, out of the
    // 500 Hz band; how far that band then lies from the box's depends on the strike's chatter:
    // 4.1 dB at the room mic on these grids, 4.5 dB on the channels' own.
    if (reporting())
    {
        DrumConfig channelsOnly = realTime;
        channelsOnly.outside.nearFieldUpTo_per_m = 0.0;
        const Recording rtChannels = record(onGridsOf(channelsOnly, realTime), samples); // on the same grids too
        worstDifference("the real-time drum without the near field, the box on its grids", rtChannels.drum, boxOnGrids.drum, fs,
                        kOctaves.back(), reportFile());
    }
}
