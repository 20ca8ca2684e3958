#pragma once
// Discrete energy of every component and coupling at time (n + 1/2) k, eq. (34)-(38), and
// the running totals of what the losses removed and the player put in or took out. With
// every loss off and the Newton snare solve, total() is constant to round-off between the
// player's actions (the quadratised solve's psi resets still remove a little, booked as
// dissipated); in every case balance() = total() + dissipated_J - injected_J is constant.

namespace snaresim
{

struct EnergyLedger
{
    double batter_J = 0.0;      // eq. (35), plus the sigma1 term of the scheme (see Membrane.h)
    double carry_J = 0.0;       // eq. (35) for the carry head
    double mallets_J = 0.0;     // eq. (37), all mallets: kinetic + mu_t+ Phi_M
    double snares_J = 0.0;      // eq. (38): wires and their collision potential
    double cavity_J = 0.0;      // (K/2) dV^{n+1} dV^n
    double dissipated_J = 0.0;  // cumulative sum of k q^n (head and wire losses) and of the
                                // quadratised snare solve's psi resets (SnareContact::stepLoss)
    double injected_J = 0.0;    // net energy from the player: strikes, retrieved mallets, snares on/off

    double total() const { return batter_J + carry_J + mallets_J + snares_J + cavity_J; }
    double balance() const { return total() + dissipated_J - injected_J; }
};

} // namespace snaresim
