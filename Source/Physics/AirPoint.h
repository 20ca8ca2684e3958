#pragma once
// A point in the air around the drum.

namespace snaresim
{

// A point in the air, metres from the drum's centre (z up, the batter at z = +H/2).
struct AirPoint
{
    double x_m = 0.0, y_m = 0.0, z_m = 0.0;
};

} // namespace snaresim
