#pragma once
// What a mallet is (Mallet.h, MalletContact.h).
// "From the schema": the model's mapping of the parameters fills the field in (DrumConfig.h).

namespace snaresim
{

// A mallet: lumped mass with power-law contact, eq. (9)-(11).
// Every field from the schema.
struct MalletSpec
{
    double mass_kg = 0.0;
    double stiffness = 0.0;       // kappa_M, N / m^alpha
    double exponent = 0.0;        // alpha (1.5 Hertz ... 3 felt)
    double contactRadius_m = 0.0; // support of g_b (raised cosine); below h: bilinear point
};

} // namespace snaresim
