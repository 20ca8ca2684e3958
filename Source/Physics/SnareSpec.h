#pragma once
// What the snare wires are and how their collision is solved (SnareWires.h, SnareContact.h).
// "From the schema": the model's mapping of the parameters fills the field in (DrumConfig.h).

namespace snaresim
{

// The snare wires: N lossy strings under the carry head, eq. (12), colliding with it through
// the power-law potential of eq. (16), both ends attached to it (eq. 17-18).
// How the snare/carry-head collision of eq. (50) is solved each step.
enum class CollisionScheme
{
    newton,     // the paper's scheme: eq. (30) solved by Newton-Raphson (iterative)
    quadratised // energy quadratisation: one linear solve per step (real time; see SnareContact.h)
};

struct SnareSpec
{
    int count = 0;            // from the schema
    double length_m = 0.30;   // along a chord through the head
    double spacing_m = 0.004; // between neighbouring wires
    double linearDensity_kg_per_m = 1.6e-3;
    double tension_N = 0.0;    // from the schema
    double sigma0_per_s = 8.0; // wire losses
    double sigma1_m2_per_s = 2.0e-4;
    double gridTension_N = 0.0; // design values of the wire grid, eq. (40) (0 / < 0: actual)
    double gridSigma1_m2_per_s = -1.0;
    double gridCoarseness = 1.0;         // h_s = coarseness * h_s,min(eq. 40); >= 1 (from the schema)
    double gridTimeStep_s = 0.0;         // as MembraneSpec::gridTimeStep_s
    double stiffness = 1.0e9;            // kappa_s, N/m per m^beta
    double exponent = 1.5;               // beta (1 ... 1.5; 1.5 is the Hertz exponent)
    double contactDamping_s_per_m = 0.0; // lambda: the force kappa xi^beta (1 + lambda dxi/dt) (Hunt and Crossley; from the schema)
    bool engaged = true;                 // false: thrown off, out of contact (from the schema)
    CollisionScheme scheme = CollisionScheme::newton; // from the schema
};

} // namespace snaresim
