// A strike of the default drum, played by the engine built for another architecture (arm64):
// exits 0 when its output is finite, sounds and stays bounded, and prints its peak and the
// vector target it ran.

#include "Drum.h"
#include "DrumConfig.h"
#include "Parameters.h"
#include "VectorTarget.h"

#include <cmath>
#include <cstdio>

int main()
{
    using namespace snaresim;
    const auto config = makeDrumConfig(ParameterSet {}, 48000.0);
    Drum drum(config);
    drum.strikeAtDefaultPoint(strikeSpeedFromVelocity(100, config.strikeSpeedMax_m_per_s));
    double peak = 0.0;
    for (int n = 0; n < 4800; ++n) // 0.1 s
    {
        const double x = drum.step();
        if (! std::isfinite(x))
        {
            std::printf("sample %d is not finite\n", n);
            return 1;
        }
        peak = std::max(peak, std::abs(x));
    }
    std::printf("0.1 s of the default drum on the %s vector target: peak %.4g\n", std::string(vectorTargetName(vectorTarget())).c_str(),
                peak);
    return peak > 1e-3 && peak < 10.0 ? 0 : 1;
}
