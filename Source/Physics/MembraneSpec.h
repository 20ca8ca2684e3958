#pragma once
// What a head is made of and how its grid is designed (Membrane.h; GridDesign.h).
// "From the schema": the model's mapping of the parameters fills the field in (DrumConfig.h).

namespace snaresim
{

// How a head stores its state and runs its free update (eq. 22).
enum class HeadPrecision
{
    double_precision, // the reference: the energy identity holds to double round-off
    single_precision  // twice the vector width; the energy identity holds to float round-off only
};

// A head: lossy 2D wave equation, eq. (2)-(4), fixed rim.
struct MembraneSpec
{
    double radius_m = 0.1778;
    double density_kg_per_m2 = 0.353; // rho_i: 10 mil PET batter
    double tension_N_per_m = 0.0;     // T_i (from the schema)
    double sigma0_per_s = 0.0;        // frequency-independent loss, 3 ln(10) / T60 (from the schema)
    double sigma1_m2_per_s = 0.0;     // frequency-dependent loss (from the schema)
    // The grid is chosen from eq. (39) for these (largest) values, so that moving the
    // tension or sigma1 below them changes coefficients only. Zero / negative: use the
    // actual tension / sigma1.
    double gridTension_N_per_m = 0.0;
    double gridSigma1_m2_per_s = -1.0;
    double gridCoarseness = 1.0; // h = coarseness * h_min(eq. 39); >= 1 (from the schema)
    // The time step the coarseness is measured against where the step is longer: the grid is
    // then coarseness * h_min(this step), or h_min of the step where that is coarser (0: the
    // step itself). A grid so designed is the same at every rate below the design rate.
    double gridTimeStep_s = 0.0;
    HeadPrecision precision = HeadPrecision::double_precision; // from the schema; the air box runs double
};

} // namespace snaresim
