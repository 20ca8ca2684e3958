#pragma once
// Which air the drum has, and the enclosed air (Cavity.h, CavityModes.h).
// "From the schema": the model's mapping of the parameters fills the field in (DrumConfig.h).

namespace snaresim
{

enum class AirModel
{
    none,   // heads uncoupled
    cavity, // uniform-pressure adiabatic cavity (Cavity.h)
    airbox  // the 3D air box around and inside the drum, heads embedded (eq. 5-8; DrumAir.h)
};

struct CavitySpec
{
    AirModel model = AirModel::cavity; // from the schema
    double shellDepth_m = 0.0;         // H: V0 = pi R^2 H (from the schema)
    double gridShellDepth_m = 0.0;     // shallowest depth the grid allows (0: the depth itself)
    double airDensity_kg_per_m3 = 1.21;
    double soundSpeed_m_per_s = 343.0;
    // The enclosed air's own modes (CavityModes.h) up to this frequency, on the heads through
    // square cells of this size (0: the uniform pressure alone, the default). Not a parameter:
    // the outside air's channels are calibrated without them (docs/MODEL.md, "Cavity modes").
    double modesUpTo_Hz = 0.0;
    double modeCellSize_m = 0.02;
};

} // namespace snaresim
