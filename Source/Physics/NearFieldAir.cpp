#include "NearFieldAir.h"

#include "AirPort.h"
#include "Bessel.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace snaresim
{

namespace
{
bool loads(const NearFieldSpec& c)
{
    return c.outside.enabled && c.outside.nearField && c.cavity.model != AirModel::airbox && c.outside.nearFieldUpTo_per_m > 0.0;
}
} // namespace

std::vector<NearFieldShape> NearFieldAir::shapes(const NearFieldSpec& c)
{
    std::vector<NearFieldShape> out;
    if (! loads(c))
        return out;
    for (int head = 0; head < 2; ++head)
    {
        const double top = c.outside.nearFieldUpTo_per_m * (head == 0 ? c.batter.radius_m : c.carry.radius_m); // largest j_mn
        std::vector<NearFieldShape> found;
        for (int m = 0;; ++m)
        {
            const int firstN = m < 2 ? 2 : 1; // (0,1) and (1,1) are the outside air's channels'
            if (m >= 2 && besselZero(m, 1) > top)
                break; // j_m1 grows with m
            for (int n = firstN;; ++n)
            {
                const double j = besselZero(m, n);
                if (j > top)
                    break;
                for (int sine = 0; sine <= (m > 0 ? 1 : 0); ++sine)
                    found.push_back({ head, m, n, sine == 1, j });
            }
        }
        std::stable_sort(found.begin(), found.end(), [](const NearFieldShape& a, const NearFieldShape& b) { return a.zero < b.zero; });
        out.insert(out.end(), found.begin(), found.end());
    }
    return out;
}

namespace
{
// For m = 0 and 1: the parts (a, b) of J_m(j r / R) {cos, sin}(m theta) along what the outside
// air's channels load, the volume (1) or first moment (x, y) and the lowest mode
// B = J_m(j_m1 r / R) {cos, sin}(m theta), so that phi - a (1 or x) - b B is orthogonal to both:
// the Gram system of int over the head, divided by pi R^2 (m = 0) or pi R^2 / 4 (m = 1, x in
// units of R); int phi B dA = 0 (the fixed rim's modes are orthogonal).
std::array<double, 2> lowerParts(const NearFieldShape& s)
{
    const double j1 = besselZero(s.m, 1), J = std::cyl_bessel_j((double) s.m + 1.0, s.zero), J1 = std::cyl_bessel_j((double) s.m + 1.0, j1);
    // m = 0: <1,1> = 1, <1,B> = 2 J_1(j1) / j1, <B,B> = J_1(j1)^2, <phi,1> = 2 J_1(j) / j
    // m = 1: <x,x> = 1, <x,B> = 4 J_2(j1) / j1, <B,B> = 2 J_2(j1)^2, <phi,x> = 4 J_2(j) / j
    const double c = s.m == 0 ? 2.0 : 4.0;
    const double g11 = 1.0, g12 = c * J1 / j1, g22 = (s.m == 0 ? 1.0 : 2.0) * J1 * J1, r1 = c * J / s.zero;
    const double det = g11 * g22 - g12 * g12;
    return { r1 * g22 / det, -r1 * g12 / det };
}
} // namespace

double NearFieldAir::shapeValue(const NearFieldShape& s, double R, double x, double y)
{
    const double r = std::hypot(x, y);
    if (r >= R)
        return 0.0;
    const double low = s.m < 2 ? std::cyl_bessel_j((double) s.m, besselZero(s.m, 1) * r / R) : 0.0;
    return shapeValue(s, R, x, y, std::cyl_bessel_j((double) s.m, s.zero * r / R), low);
}

double NearFieldAir::shapeValue(const NearFieldShape& s, double R, double x, double y, double J, double lowest)
{
    if (std::hypot(x, y) >= R)
        return 0.0;
    const double angle = s.m * std::atan2(y, x), trig = s.m == 0 ? 1.0 : (s.sine ? std::sin(angle) : std::cos(angle));
    if (s.m >= 2)
        return J * trig;
    // less the parts along the channels' coordinate and the lowest mode (lowerParts)
    const auto [a, b] = lowerParts(s);
    const double along = s.m == 0 ? 1.0 : (s.sine ? y : x) / R;
    return (J - b * lowest) * trig - a * along;
}

double NearFieldAir::kineticReserve(const NearFieldSpec& c, bool ofBatter)
{
    // the lowest zero of the shapes is j_21 (shapes())
    const double R = ofBatter ? c.batter.radius_m : c.carry.radius_m;
    return loads(c) && besselZero(2, 1) <= c.outside.nearFieldUpTo_per_m * R ? c.outside.nearFieldReserve : 0.0;
}

NearFieldAir::NearFieldAir(const NearFieldSpec& c, double timeStep)
    : list(shapes(c)), k(timeStep), budget(c.outside.nearFieldReserve), damping(std::clamp(c.outside.nearFieldDamping, 0.0, 1.0)),
      inside(c.cavity.model == AirModel::cavity && c.cavityModesUpTo_Hz <= 0.0)
{
    const size_t n = list.size();
    for (auto* v : { &mu, &omega, &K, &M, &D, &cellArea, &headArea })
        v->assign(n, 0.0);
    at.assign(n);
    setSpec(c);
}

void NearFieldAir::setSpec(const NearFieldSpec& c)
{
    radius = { c.batter.radius_m, c.carry.radius_m };
    density = { c.batter.density_kg_per_m2, c.carry.density_kg_per_m2 };
    tension = { c.batter.tension_N_per_m, c.carry.tension_N_per_m };
    airDensity = c.cavity.airDensity_kg_per_m3;
    depth = c.cavity.shellDepth_m;
    for (size_t i = 0; i < list.size(); ++i)
    {
        const double kw = list[i].zero / radius[(size_t) list[i].head];
        mu[i] = airDensity * (1.0 + (inside ? 1.0 / std::tanh(kw * depth) : 0.0)) / kw;
        setChannel(i);
    }
}

void NearFieldAir::setNorms(int i, double cells, double head)
{
    cellArea[(size_t) i] = cells;
    headArea[(size_t) i] = head;
    setChannel((size_t) i);
}

void NearFieldAir::setChannel(size_t i)
{
    if (cellArea[i] <= 0.0 || headArea[i] <= 0.0)
    {
        K[i] = D[i] = 0.0; // no norms yet (or no cell on the shape): no force
        M[i] = 1.0;
        return;
    }
    const size_t h = (size_t) list[i].head;
    const double rho = density[h];
    const double Meff = mu[i] * headArea[i] / (cellArea[i] * cellArea[i]);
    // the mode's frequency with the air's mass on it
    const double w = list[i].zero / radius[h] * std::sqrt(std::max(tension[h], 0.0) / rho) / std::sqrt(1.0 + mu[i] / rho);
    omega[i] = w;
    // the largest corner within the budget: 3 K A_cells k^2 / rho = 3 Meff (wc^2 - w^2) A_cells k^2 / rho <= budget
    const double wc2 = w * w + budget * rho / (3.0 * cellArea[i] * Meff * k * k);
    K[i] = Meff * (wc2 - w * w);
    M[i] = K[i] / wc2; // Meff (1 - w^2 / wc^2): Meff at w
    D[i] = damping * 0.25 * K[i] * k;
}

void NearFieldAir::computeFree()
{
    for (size_t i = 0; i < list.size(); ++i)
    {
        const airport::Step s = airport::dampedStep(k, K[i], M[i], D[i], at.qPrev[i], at.qNow[i], at.zPrev[i], at.zNow[i], at.vPrev[i]);
        at.zNext[i] = s.zNext;
        at.vNext[i] = s.vNext;
        at.P[i] = s.onHeads;
    }
}

double NearFieldAir::energy() const
{
    double e = 0.0;
    for (size_t i = 0; i < list.size(); ++i)
        e += airport::dampedEnergy(k, K[i], M[i], D[i], at.qNext[i], at.qNow[i], at.zNext[i], at.zNow[i], at.vNext[i]);
    return e;
}

double NearFieldAir::stepLoss() const
{
    double loss = 0.0;
    for (size_t i = 0; i < list.size(); ++i)
        loss += airport::damperLoss(k, D[i], at.qNext[i], at.qPrev[i], at.zNext[i], at.zPrev[i]);
    return loss;
}

void NearFieldAir::advance() { at.advance(); }

void NearFieldAir::clear() { at.clear(); }

} // namespace snaresim
