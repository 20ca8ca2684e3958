#pragma once
// Coupling between the batter and the mallets: the power-law contact of eq. (10)-(11),
// discretised as eq. (26)-(27) and solved each step from eq. (44)-(45) by Newton-Raphson.
// Several mallets whose patches overlap are solved together: their eq. (44) becomes a small
// vector equation r + Gamma psi(r) + b = 0 with Gamma symmetric positive definite.

#include "Membrane.h"
#include "Mallet.h"

#include <Eigen/Core>

#include <span>

namespace snaresim
{

struct ContactSolveResult
{
    int iterations = 0;     // Newton iterations (0 when no mallet could touch)
    bool fallback = false;  // Newton did not converge within its cap; bracketed fallback used
};

class MalletContact
{
public:
    static constexpr int maxMallets = 16;
    static constexpr int maxNewtonIterations = 50;
    static constexpr int maxFallbackSweeps = 200;
    // Convergence: Newton step below tolerance * (|r| + |a| + |b|), near round-off.
    static constexpr double tolerance = 1.0e-14; // Newton step / (|r| + |a| + |b|)

    // Given the free update w^{n+1} of the head and the mallets at n, n-1: find the contact
    // forces, add them to the head's w^{n+1} and set each mallet's z^{n+1} and eta^{n+1}.
    ContactSolveResult step(Membrane& head, std::span<Mallet> mallets);

    // mu_t+ Phi_M at n+1/2 summed over the mallets (second term of eq. 37).
    static double potentialEnergy(std::span<const Mallet> mallets);


private:
    using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, maxMallets, maxMallets>;
    using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, maxMallets, 1>;

    bool solveJoint(std::span<Mallet> mallets, int m, int& iterations);
    void solveGaussSeidel(std::span<Mallet> mallets, int m, int& iterations);

    int members[maxMallets] {};   // indices of mallets that may touch this step
    Mat gamma;
    Vec a, b, r, f;
};

} // namespace snaresim
