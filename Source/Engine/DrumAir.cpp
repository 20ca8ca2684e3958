#include "DrumAir.h"

#include <algorithm>

namespace snaresim
{

void DrumAir::build(const DrumConfig& cfg, Membrane& batter, Membrane& carry)
{
    const double k = 1.0 / cfg.sampleRate_Hz, H = cfg.cavity.shellDepth_m;
    box = std::make_unique<AirBox>(cfg.airBoxSpec(), k);
    box->setThreads(cfg.air.threads);
    top = std::make_unique<HeadEmbedding>(*box, batter, 0.5 * H);     // closes the shell's top end
    bottom = std::make_unique<HeadEmbedding>(*box, carry, -0.5 * H);  // and its bottom end
    micCount = cfg.airMicPoints(points);
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
