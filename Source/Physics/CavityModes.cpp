#include "CavityModes.h"

#include "AirPort.h"
#include "Bessel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace snaresim
{

namespace
{
// H_min: the shallowest depth the grid allows (Cavity::kineticReserve's).
double shallowest(const CavitySpec& s) { return s.gridShellDepth_m > 0.0 ? std::min(s.gridShellDepth_m, s.shellDepth_m) : s.shellDepth_m; }
// The depth the air has (Cavity::setSpec's).
double depthOf(const CavitySpec& s) { return s.gridShellDepth_m > 0.0 ? std::max(s.shellDepth_m, s.gridShellDepth_m) : s.shellDepth_m; }

// int_0^R J_m(j r / R)^2 r dr, times int {cos, sin}^2(m theta) dtheta: int Phi^2 dA over a face.
double faceNorm(const CavityMode& mode, double R)
{
    const double j = mode.zero;
    const double radial =
        j == 0.0 ? 0.5 * R * R
                 : 0.5 * R * R * (1.0 - (double) (mode.m * mode.m) / (j * j)) * std::pow(std::cyl_bessel_j((double) mode.m, j), 2.0);
    return radial * (mode.m == 0 ? 2.0 * std::numbers::pi : std::numbers::pi);
}
// int cos^2(p pi z / H) dz over the depth.
double axialNorm(int p, double H) { return p == 0 ? H : 0.5 * H; }

double omegaOf(const CavityMode& mode, double R, double H, double c)
{
    const double a = mode.zero / R, b = mode.p * std::numbers::pi / H;
    return c * std::sqrt(a * a + b * b);
}
} // namespace

std::vector<CavityMode> CavityModes::below(const CavitySpec& spec, double upTo_Hz, double R)
{
    std::vector<CavityMode> out;
    if (spec.model != AirModel::cavity || upTo_Hz <= 0.0)
        return out;
    const double H = depthOf(spec), c = spec.soundSpeed_m_per_s, top = 2.0 * std::numbers::pi * upTo_Hz;
    std::vector<std::pair<double, CavityMode>> found;
    for (int m = 0; m < 64; ++m)
    {
        bool any = false;
        for (int n = (m == 0 ? 0 : 1); n < 64; ++n) // (0, 0): the uniform face, its p >= 1 modes
        {
            CavityMode mode;
            mode.m = m;
            mode.n = n;
            mode.zero = n == 0 ? 0.0 : besselPrimeZero(m, n);
            if (c * mode.zero / R > top)
                break;
            any = true;
            for (int p = (n == 0 ? 1 : 0);; ++p)
            {
                mode.p = p;
                const double w = omegaOf(mode, R, H, c);
                if (w > top)
                    break;
                for (int sine = 0; sine <= (m > 0 ? 1 : 0); ++sine)
                {
                    mode.sine = sine == 1;
                    found.push_back({ w, mode });
                }
            }
        }
        if (! any)
            break;
    }
    std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<std::array<int, 3>> shapes;
    for (auto& [w, mode] : found)
    {
        const std::array<int, 3> key { mode.m, mode.n, mode.sine ? 1 : 0 };
        const auto at = std::find(shapes.begin(), shapes.end(), key);
        mode.shape = (int) (at - shapes.begin());
        if (at == shapes.end())
            shapes.push_back(key);
        out.push_back(mode);
    }
    return out;
}

double CavityModes::faceShape(const CavityMode& mode, double R, double x, double y)
{
    if (mode.zero == 0.0)
        return 1.0;
    const double r = std::hypot(x, y), theta = std::atan2(y, x);
    const double radial = std::cyl_bessel_j((double) mode.m, mode.zero * std::min(r, R) / R);
    return radial * (mode.sine ? std::sin(mode.m * theta) : std::cos(mode.m * theta));
}

// Mode i's negative energy is at most (K_i/4)(dt+ q_i)^2 k^2 (AirPort.h), and (dt+ q)^2 <= 2 (dt+ B)^2
// + 2 (dt+ C)^2 with B, C the two heads' shares. On one head the modes of one face shape s share
// B_s = h^2 psi_s . w, (dt+ B_s)^2 <= A_s h^2 |dt+ w|^2 (A_s = int psi_s^2 dA), and the shapes are
// orthogonal on the face: the share of the head's kinetic energy (rho/2) h^2 |dt+ w|^2 is
// lambda k^2 / rho with lambda = max_s sum_{i in s} K_i A_s = rho_a c_a^2 max_s sum 1 / int cos^2(p pi z/H) dz,
// at the shallowest depth; doubled for margin (the cells make the shapes nearly, not exactly, orthogonal).
double CavityModes::kineticReserve(const CavitySpec& spec, double upTo_Hz, double R, double density, double k)
{
    const std::vector<CavityMode> modes = below(spec, upTo_Hz, R);
    if (modes.empty())
        return 0.0;
    const double H = shallowest(spec);
    std::vector<double> perShape;
    for (const CavityMode& mode : modes)
    {
        if ((size_t) mode.shape >= perShape.size())
            perShape.resize((size_t) mode.shape + 1, 0.0);
        perShape[(size_t) mode.shape] += 1.0 / axialNorm(mode.p, H);
    }
    const double lambda =
        spec.airDensity_kg_per_m3 * spec.soundSpeed_m_per_s * spec.soundSpeed_m_per_s * *std::max_element(perShape.begin(), perShape.end());
    return 2.0 * lambda * k * k / density;
}

CavityModes::CavityModes(const CavitySpec& spec, double upTo_Hz, double R, double timeStep) : modes(below(spec, upTo_Hz, R)), k(timeStep)
{
    for (const CavityMode& mode : modes)
        numShapes = std::max(numShapes, mode.shape + 1);
    K.assign(modes.size(), 0.0);
    M.assign(modes.size(), 0.0);
    at.assign(modes.size());
    for (const CavityMode& mode : modes)
        faceArea.push_back(faceNorm(mode, R));
    radius = R;
    setSpec(spec);
}

void CavityModes::setSpec(const CavitySpec& spec)
{
    const double H = depthOf(spec), c = spec.soundSpeed_m_per_s;
    for (size_t i = 0; i < modes.size(); ++i)
    {
        const double w = omegaOf(modes[i], radius, H, c);
        K[i] = spec.airDensity_kg_per_m3 * c * c / (faceArea[i] * axialNorm(modes[i].p, H));
        M[i] = K[i] / (w * w);
    }
    depth = H;
    speed = c;
}

double CavityModes::frequency_Hz(int i) const { return omegaOf(modes[(size_t) i], radius, depth, speed) / (2.0 * std::numbers::pi); }

void CavityModes::computeFree()
{
    for (size_t i = 0; i < modes.size(); ++i)
    {
        const airport::Step s = airport::step(k, K[i], M[i], 0.0, at.qNow[i], at.zPrev[i], at.zNow[i], at.vPrev[i]);
        at.zNext[i] = s.zNext;
        at.vNext[i] = s.vNext;
        at.P[i] = s.onHeads;
    }
}

double CavityModes::energy() const
{
    double e = 0.0;
    for (size_t i = 0; i < modes.size(); ++i)
        e += airport::energy(K[i], M[i], at.qNext[i], at.qNow[i], at.zNext[i], at.zNow[i], at.vNext[i]);
    return e;
}

void CavityModes::advance() { at.advance(); }

void CavityModes::clear() { at.clear(); }

} // namespace snaresim
