#pragma once
// The outside air's channels and near field (OutsideAir.h, NearFieldAir.h).
// "From the schema": the model's mapping of the parameters fills the field in (DrumConfig.h).

namespace snaresim
{

// The outside air of the reduced model (OutsideAir.h): six radiation channels, each a mass M in
// parallel with a resistance R, calibrated against the drum in the air box (docs/MODEL.md,
// "Outside air"). Not used in the air box, which is the outside air itself.
struct RadiationChannelSpec
{
    double mass = 0.0;       // M: kg/m^4 on a volume, kg/m^6 on a first moment
    double resistance = 0.0; // R: Pa s/m^3 on a volume, Pa s/m^5 on a first moment; infinite: lossless
};

struct OutsideAirSpec
{
    bool enabled = false; // from the schema
    // Lab/calibrate_outside_air.py against the 1.4 m and 1.8 m air boxes (docs/MODEL.md)
    RadiationChannelSpec monopole { 1.311, 1.418e4 }; // V_b - V_c: the volume pushed out
    RadiationChannelSpec dipole { 1.294, 6.579e4 };   // V_b + V_c: the volume carried through
    RadiationChannelSpec tiltSum { 251.8, 3.185e7 };  // X_b + X_c: both heads' first moments together
    RadiationChannelSpec tiltDiff { 130.2, 4.488e7 }; // X_b - X_c: against each other
    double cornerLimit_Hz = 3000.0;                   // the compliance 1/K behind each channel: sqrt(K/M) at most this
    double reserve = 0.05;                            // and at most this share of the lighter head's kinetic energy
    // The near field's mass on the heads' modes above (0,1) and (1,1) (NearFieldAir.h): those of
    // wavenumber j_mn / R up to this (rad/m; 0: none; 75: four 2 cm cells a wavelength), on at
    // most this share of each head's kinetic energy, with this share of the largest damper the
    // explicit coupling allows across each channel's compliance (0: lossless).
    bool nearField = true; // the near field with the channels (the schema's near_field)
    double nearFieldUpTo_per_m = 60.0;
    double nearFieldReserve = 0.08;
    double nearFieldDamping = 1.0;
    double nearFieldCellSize_m = 0.04; // its shapes' cells: whole groups of the microphones' cells
};

} // namespace snaresim
