#include "DrumAir.h"

#include <algorithm>

namespace snaresim
{

void DrumAir::build(const AirBoxSpec& spec, int threads, double H, double k, Membrane& batter, Membrane& carry)
{
    box = std::make_unique<AirBox>(spec, k);
    box->setThreads(threads);
    top = std::make_unique<HeadEmbedding>(*box, batter, 0.5 * H);    // closes the shell's top end
    bottom = std::make_unique<HeadEmbedding>(*box, carry, -0.5 * H); // and its bottom end
}

void DrumAir::placeMics(const std::array<AirPoint, DrumAirSpec::maxMics>& at, int count)
{
    points = at;
    micCount = count;
}

void DrumAir::listen()
{
    for (int i = 0; i < micCount; ++i)
    {
        const AirPoint& p = points[(size_t) i];
        pressures[(size_t) i] = box->pressure(p.x_m, p.y_m, p.z_m);
    }
}

void DrumAir::refresh()
{
    if (! box)
        return;
    top->refresh();
    bottom->refresh();
}

void DrumAir::clear()
{
    if (! box)
        return;
    box->clear();
    top->clear();
    bottom->clear();
    pressures.fill(0.0);
}

} // namespace snaresim
