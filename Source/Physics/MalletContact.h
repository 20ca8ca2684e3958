#pragma once
// Coupling between the batter and the mallets: the power-law contact of eq. (10)-(11),
// discretised as eq. (26)-(27) and solved each step from eq. (44)-(45) by Newton-Raphson.
// Several mallets whose patches overlap are solved together: their eq. (44) becomes a small
// vector equation r + Gamma psi(r) + b = 0 with Gamma symmetric positive definite.
// It owns the contact forces and the contact potential mu_t+ Phi_M (second term of eq. 37).

#include "Mallet.h"
#include "Membrane.h"

#include <Eigen/Core>

#include <span>

namespace snaresim
{

struct ContactSolveResult
{
    int iterations = 0;    // Newton iterations (0 when no mallet could touch)
    bool fallback = false; // Newton did not converge within its cap; bracketed fallback used
};

class MalletContact
{
public:
    static constexpr int maxMallets = 16;
    static constexpr int maxNewtonIterations = 50;
    static constexpr int maxFallbackSweeps = 200;
    // Convergence: Newton step below tolerance * (|r| + |a| + |b|), near round-off.
    static constexpr double tolerance = 1.0e-14; // Newton step / (|r| + |a| + |b|)

    // The batter and the mallets it couples (both must outlive it; the mallets never move).
    MalletContact(Membrane& batter, std::span<Mallet> mallets);

    // After the free updates of the batter (w*) and the mallets in play (z*): find the contact
    // forces, add them to the batter's w^{n+1} and the mallets' z^{n+1}, and set each eta^{n+1}.
    ContactSolveResult step();

    // mu_t+ Phi_M at n+1/2 summed over the mallets in play (second term of eq. 37).
    double energy() const;
    double stepLoss() const { return 0.0; } // conservative
    // One mallet's mu_t+ Phi_M at n+1/2 and at n-1/2 (0 when parked).
    static double potentialEnergy(const Mallet& mallet);
    static double potentialEnergyBeforeStep(const Mallet& mallet);

private:
    using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, maxMallets, maxMallets>;
    using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, maxMallets, 1>;

    bool solveJoint(std::span<Mallet> mallets, int m, int& iterations);
    void solveGaussSeidel(std::span<Mallet> mallets, int m, int& iterations);

    int members[maxMallets] {}; // indices of mallets that may touch this step
    Mat gamma;
    Vec a, b, r, f;

    Membrane& batter;
    std::span<Mallet> malletSet;
};

} // namespace snaresim
