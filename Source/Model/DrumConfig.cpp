#include "DrumConfig.h"

#include "Cavity.h"
#include "CavityModes.h"
#include "GridDesign.h"
#include "HostRateInterpolator.h"
#include "Membrane.h"
#include "NearFieldAir.h"
#include "OutsideAir.h"
#include "SnareWires.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace snaresim
{

namespace
{
// Quality's grids are designed at 48 kHz: at a lower rate the heads and wires keep the grids
// they have at 48 kHz where those are stable (designed with the 48 kHz step's reserve:
// designReserve), so the drum has the same nodes at 44.1 kHz and at the 32 and 33.075 kHz that
// simulate the default's grids (HostRateInterpolator.h).
constexpr double kGridDesignStep_s = 1.0 / 48000.0;

void require(bool ok, const char* what, double value)
{
    if (ok)
        return;
    std::ostringstream msg;
    msg << what << " (got " << value << ")";
    throw std::invalid_argument(msg.str());
}

void validateMembrane(const MembraneSpec& m, double k, double reserve, double designReserve)
{
    require(std::isfinite(m.radius_m) && m.radius_m > 0.01 && m.radius_m < 2.0, "head radius must be within 0.01..2 m", m.radius_m);
    require(std::isfinite(m.density_kg_per_m2) && m.density_kg_per_m2 > 0.0, "head density must be positive", m.density_kg_per_m2);
    require(std::isfinite(m.tension_N_per_m) && m.tension_N_per_m > 0.0, "head tension must be positive", m.tension_N_per_m);
    require(std::isfinite(m.sigma0_per_s) && m.sigma0_per_s >= 0.0, "head sigma0 must be >= 0", m.sigma0_per_s);
    require(std::isfinite(m.sigma1_m2_per_s) && m.sigma1_m2_per_s >= 0.0, "head sigma1 must be >= 0", m.sigma1_m2_per_s);
    require(std::isfinite(m.gridCoarseness) && m.gridCoarseness >= 1.0,
            "grid coarseness must be >= 1: a grid finer than the stability bound (eq. 39) is unstable", m.gridCoarseness);
    require(m.gridTension_N_per_m <= 0.0 || m.gridTension_N_per_m >= m.tension_N_per_m,
            "the grid's design tension must not be below the tension", m.gridTension_N_per_m);
    require(m.gridSigma1_m2_per_s < 0.0 || m.gridSigma1_m2_per_s >= m.sigma1_m2_per_s, "the grid's design sigma1 must not be below sigma1",
            m.gridSigma1_m2_per_s);
    const double h = Membrane::gridSpacing(m, k, reserve, designReserve);
    const double pointsPerRadius = m.radius_m / h;
    require(pointsPerRadius >= 4.0,
            "the head grid would have fewer than 4 points per radius at this sample rate and coarseness; raise the sample rate or lower "
            "the coarseness",
            pointsPerRadius);
    require(pointsPerRadius <= 1500.0, "the head grid would be too large (more than 1500 points per radius)", pointsPerRadius);
}
void validateAirBox(const DrumConfig& c)
{
    const DrumAirSpec& a = c.airBox;
    require(a.walls == AirWalls::absorbing || a.walls == AirWalls::reflecting, "air box walls must be absorbing or reflecting",
            (double) a.walls);
    require(std::isfinite(a.sigma_m) && a.sigma_m >= 0.0 && a.sigma_m <= 1e-3, "air box sigma_a must be within 0..1e-3 m", a.sigma_m);
    require(std::isfinite(a.gridCoarseness) && a.gridCoarseness >= 1.0 && a.gridCoarseness <= 10.0,
            "air box grid coarseness must be within 1..10: a grid finer than the stability bound (eq. 41) is unstable", a.gridCoarseness);
    require(a.threads >= 1 && a.threads <= 64, "air box threads must be within 1..64", a.threads);
    require(a.numMics >= 0 && a.numMics <= DrumAirSpec::maxMics, "number of air microphones must be within 0..8", a.numMics);
    require(std::isfinite(a.margin_m) && a.margin_m >= 0.0, "air box margin must be >= 0", a.margin_m);
    const AirBoxSpec box = c.airBoxSpec();
    const double h = AirBox::gridSpacing(box, 1.0 / c.sampleRate_Hz);
    const double R = c.batter.radius_m, H = c.cavity.shellDepth_m;
    const char* axis[3] = { "x", "y", "z" };
    for (int i = 0; i < 3; ++i)
    {
        const double L = box.size_m[(size_t) i];
        require(std::isfinite(L) && L > 0.0 && L <= 20.0, "air box sides must be within 0..20 m", L);
        // the drum with two cells of air beyond it (the embedding's and the shell's needs, eq. 41 grid)
        const double need = (i < 2 ? 2.0 * R : H) + 4.0 * h;
        if (L < need)
        {
            std::ostringstream msg;
            msg << "the air box does not hold the drum: its " << axis[i] << " side is " << L << " m, but the drum (radius " << R
                << " m, shell depth " << H << " m) needs at least " << need << " m with two air cells (h_a = " << h << " m) around it";
            throw std::invalid_argument(msg.str());
        }
    }
    require(H >= 3.0 * h, "the shell depth must be at least three air cells (h_a of eq. 41) for the air between the heads", H / h);
    const double points = std::ceil(box.size_m[0] / h) * std::ceil(box.size_m[1] / h) * std::ceil(box.size_m[2] / h);
    require(points <= 6e7, "the air box would have too many points (limit 6e7); make it smaller or lower the sample rate", points);
    std::array<AirPoint, DrumAirSpec::maxMics> mics;
    const int n = c.airMicPoints(mics);
    for (int m = 0; m < n; ++m)
    {
        const AirPoint& p = mics[(size_t) m];
        const double v[3] = { p.x_m, p.y_m, p.z_m };
        for (int i = 0; i < 3; ++i)
            require(std::isfinite(v[i]) && std::abs(v[i]) <= 0.5 * box.size_m[(size_t) i] - h,
                    "air microphones must lie inside the air box, a cell from its walls (coordinate in m)", v[i]);
    }
}
} // namespace

void DrumConfig::validate() const
{
    require(std::isfinite(sampleRate_Hz) && sampleRate_Hz >= 1000.0 && sampleRate_Hz <= 768000.0,
            "sample rate must be within 1000..768000 Hz", sampleRate_Hz);
    const double k = 1.0 / sampleRate_Hz;
    const int up = outputUp(), down = outputDown();
    const int twos = up % 3 == 0 ? up / 3 : up; // a power of two
    require(std::isfinite(outputRate()) && std::abs(outputRate() * down - up * sampleRate_Hz) <= 1e-9 * outputRate() &&
                (up == 1 || (up <= 32 && up > down && (twos & (twos - 1)) == 0 && cavity.model != AirModel::airbox)),
            "the output rate must be the sample rate times 2^n or 3 * 2^n / 2 or 2^n / 3, up to 32 (1 in the air box)", outputRate());
    require(cavity.model == AirModel::none || cavity.model == AirModel::cavity || cavity.model == AirModel::airbox, "unknown air model",
            (double) cavity.model);
    require(std::isfinite(cavity.shellDepth_m) && cavity.shellDepth_m >= 0.02 && cavity.shellDepth_m <= 1.0,
            "shell depth must be within 0.02..1 m", cavity.shellDepth_m);
    require(std::isfinite(cavity.gridShellDepth_m) && cavity.gridShellDepth_m >= 0.0, "grid shell depth must be >= 0",
            cavity.gridShellDepth_m);
    require(std::isfinite(cavity.airDensity_kg_per_m3) && cavity.airDensity_kg_per_m3 > 0.0, "air density must be positive",
            cavity.airDensity_kg_per_m3);
    require(std::isfinite(cavity.soundSpeed_m_per_s) && cavity.soundSpeed_m_per_s > 0.0, "speed of sound must be positive",
            cavity.soundSpeed_m_per_s);
    require(std::abs(carry.radius_m - batter.radius_m) < 1e-12, "both heads must have the same radius", carry.radius_m);
    for (const RadiationChannelSpec* ch : { &outside.monopole, &outside.dipole, &outside.tiltSum, &outside.tiltDiff })
    {
        require(std::isfinite(ch->mass) && ch->mass > 0.0, "an outside-air channel's mass must be positive", ch->mass);
        require(ch->resistance > 0.0, "an outside-air channel's resistance must be positive (infinite: lossless)", ch->resistance);
    }
    require(std::isfinite(outside.cornerLimit_Hz) && outside.cornerLimit_Hz > 0.0, "the outside air's corner limit must be positive",
            outside.cornerLimit_Hz);
    require(std::isfinite(outside.reserve) && outside.reserve > 0.0 && outside.reserve <= 0.2,
            "the outside air's reserve must be within 0..0.2", outside.reserve);
    require(std::isfinite(outside.nearFieldUpTo_per_m) && outside.nearFieldUpTo_per_m >= 0.0 && outside.nearFieldUpTo_per_m <= 300.0,
            "the near field's largest wavenumber must be within 0..300 rad/m", outside.nearFieldUpTo_per_m);
    require(std::isfinite(outside.nearFieldReserve) && outside.nearFieldReserve > 0.0 && outside.nearFieldReserve <= 0.2,
            "the near field's reserve must be within 0..0.2", outside.nearFieldReserve);
    require(std::isfinite(outside.nearFieldDamping) && outside.nearFieldDamping >= 0.0 && outside.nearFieldDamping <= 1.0,
            "the near field's damping must be within 0..1", outside.nearFieldDamping);
    require(std::isfinite(outside.nearFieldCellSize_m) && outside.nearFieldCellSize_m > 0.0 && outside.nearFieldCellSize_m <= 0.1,
            "the near field's cells must be within 0..0.1 m", outside.nearFieldCellSize_m);
    for (const bool ofBatter : { true, false })
    {
        const MembraneSpec* m = ofBatter ? &batter : &carry;
        const double reserve = kineticReserve(ofBatter);
        require(reserve < 0.5, "the cavity is too stiff for this sample rate (shell too shallow)", reserve);
        validateMembrane(*m, k, reserve, designReserve(ofBatter));
    }
    require(snares.count >= 0 && snares.count <= 64, "number of snare wires must be within 0..64", snares.count);
    require(std::isfinite(snares.length_m) && snares.length_m > 0.05, "snare length must be above 0.05 m", snares.length_m);
    require(std::isfinite(snares.spacing_m) && snares.spacing_m >= 0.0, "snare spacing must be >= 0", snares.spacing_m);
    require(std::isfinite(snares.linearDensity_kg_per_m) && snares.linearDensity_kg_per_m > 0.0, "snare density must be positive",
            snares.linearDensity_kg_per_m);
    require(std::isfinite(snares.tension_N) && snares.tension_N > 0.0, "snare tension must be positive", snares.tension_N);
    require(snares.gridTension_N <= 0.0 || snares.gridTension_N >= snares.tension_N,
            "the snare grid's design tension must not be below the tension", snares.gridTension_N);
    require(std::isfinite(snares.sigma0_per_s) && snares.sigma0_per_s >= 0.0, "snare sigma0 must be >= 0", snares.sigma0_per_s);
    require(std::isfinite(snares.sigma1_m2_per_s) && snares.sigma1_m2_per_s >= 0.0, "snare sigma1 must be >= 0", snares.sigma1_m2_per_s);
    require(std::isfinite(snares.gridCoarseness) && snares.gridCoarseness >= 1.0,
            "snare grid coarseness must be >= 1: a grid finer than the stability bound (eq. 40) is unstable", snares.gridCoarseness);
    require(std::isfinite(snares.stiffness) && snares.stiffness > 0.0, "snare contact stiffness must be positive", snares.stiffness);
    require(std::isfinite(snares.contactDamping_s_per_m) && snares.contactDamping_s_per_m >= 0.0, "snare contact damping must be >= 0",
            snares.contactDamping_s_per_m);
    require(std::isfinite(snares.exponent) && snares.exponent >= 1.0 && snares.exponent <= 4.0,
            "snare contact exponent must be within 1..4", snares.exponent);
    if (snares.count > 0)
    {
        const SnareSpec fitted = fittedSnares();
        require(fitted.length_m >= 0.5 * snares.length_m && fitted.length_m >= 0.1,
                "the snare wires do not fit on the carry head's grid at this sample rate and coarseness", fitted.length_m);
        const double intervals = fitted.length_m / SnareWires::gridSpacing(snares, k);
        require(intervals >= 4.0, "the snare wire grid would have fewer than 4 intervals at this sample rate", intervals);
        require(intervals <= 4000.0, "the snare wire grid would be too large", intervals);
    }
    require(std::isfinite(mallet.mass_kg) && mallet.mass_kg > 0.0, "mallet mass must be positive", mallet.mass_kg);
    require(std::isfinite(mallet.stiffness) && mallet.stiffness > 0.0, "mallet stiffness must be positive", mallet.stiffness);
    require(std::isfinite(mallet.exponent) && mallet.exponent >= 1.0 && mallet.exponent <= 4.0, "mallet exponent alpha must be within 1..4",
            mallet.exponent);
    require(std::isfinite(mallet.contactRadius_m) && mallet.contactRadius_m >= 0.0 && mallet.contactRadius_m < 0.5 * batter.radius_m,
            "mallet contact radius must be within 0..R/2", mallet.contactRadius_m);
    require(numMallets >= 1 && numMallets <= 16, "number of mallets must be within 1..16", numMallets);
    require(std::isfinite(strikeSpeedMax_m_per_s) && strikeSpeedMax_m_per_s > 0.0 && strikeSpeedMax_m_per_s <= 50.0,
            "maximum strike speed must be within 0..50 m/s", strikeSpeedMax_m_per_s);
    require(std::isfinite(strikeRadius_frac) && strikeRadius_frac >= 0.0 && strikeRadius_frac <= 0.95,
            "strike position must be within 0..0.95 R", strikeRadius_frac);
    require(std::isfinite(mics.reach_m) && mics.reach_m > 0.0 && mics.reach_m <= 20.0, "microphone reach must be within 0..20 m",
            mics.reach_m);
    require(std::isfinite(mics.cellSize_m) && mics.cellSize_m > 0.0 && mics.cellSize_m <= batter.radius_m,
            "microphone cell size must be within 0..R", mics.cellSize_m);
    require(std::isfinite(mics.fineCellSize_m) && mics.fineCellSize_m > 0.0 && mics.fineCellSize_m <= mics.cellSize_m,
            "microphone fine cell size must be within 0..cell size", mics.fineCellSize_m);
    for (const AirPoint* p : { &mics.top, &mics.bottom, &mics.room })
    {
        const double r = std::hypot(p->x_m, p->y_m), d = std::hypot(r, p->z_m);
        require(std::isfinite(d) && d <= mics.reach_m, "microphones must lie within the reach of the drum's centre (m)", d);
        const double outside = std::max(std::abs(p->z_m) - 0.5 * cavity.shellDepth_m, r - batter.radius_m);
        require(outside >= 0.005, "microphones must stand at least 5 mm outside the drum (m)", outside);
    }
    require(mics.top.z_m > 0.0 && mics.bottom.z_m < 0.0, "the top microphone must face the batter and the bottom one the carry head",
            mics.top.z_m);
    for (double g : { mics.topGain, mics.bottomGain, mics.roomGain, mics.mixTop, mics.mixBottom, mics.mixRoom })
        require(std::isfinite(g), "microphone gains must be finite", g);
    require(std::isfinite(outputGain), "output gain must be finite", outputGain);
    require(std::isfinite(room.reverberationTime_s) && room.reverberationTime_s >= 0.0 && room.reverberationTime_s <= 10.0,
            "room reverberation time must be within 0..10 s", room.reverberationTime_s);
    require(std::isfinite(room.volume_m3) && room.volume_m3 > 0.0 && room.volume_m3 <= 1e5, "room volume must be within 0..1e5 m^3",
            room.volume_m3);
    if (cavity.model == AirModel::airbox)
        validateAirBox(*this);
}

AirBoxSpec DrumConfig::airBoxSpec() const
{
    const double R = batter.radius_m, H = cavity.shellDepth_m;
    const double extent[3] = { 2.0 * R, 2.0 * R, H };
    AirBoxSpec s;
    s.soundSpeed_m_per_s = cavity.soundSpeed_m_per_s;
    s.density_kg_per_m3 = cavity.airDensity_kg_per_m3;
    s.sigma_m = airBox.sigma_m;
    s.gridCoarseness = airBox.gridCoarseness;
    for (int a = 0; a < 3; ++a)
        s.size_m[(size_t) a] = airBox.size_m[(size_t) a] > 0.0 ? airBox.size_m[(size_t) a] : extent[a] + 2.0 * airBox.margin_m;
    s.walls = airBox.walls;
    s.shell = true;
    s.shellRadius_m = R;
    s.shellDepth_m = H;
    s.shellEnds = ShellEnds::closed;
    return s;
}

int DrumConfig::airMicPoints(std::array<AirPoint, DrumAirSpec::maxMics>& out) const
{
    if (airBox.numMics > 0)
    {
        const int n = std::min(airBox.numMics, DrumAirSpec::maxMics);
        std::copy_n(airBox.mics.begin(), n, out.begin());
        return n;
    }
    const AirBoxSpec box = airBoxSpec();
    const double h = AirBox::gridSpacing(box, 1.0 / sampleRate_Hz);
    const AirPoint* own[3] = { &mics.top, &mics.bottom, &mics.room };
    for (int m = 0; m < 3; ++m)
    {
        const double v[3] = { own[m]->x_m, own[m]->y_m, own[m]->z_m };
        double c[3];
        for (int a = 0; a < 3; ++a)
        {
            const double limit = 0.5 * box.size_m[(size_t) a] - 1.5 * h;
            c[a] = std::clamp(v[a], -limit, limit);
        }
        out[(size_t) m] = { c[0], c[1], c[2] };
    }
    return 3;
}

SnareSpec DrumConfig::fittedSnares() const
{
    SnareSpec s = snares;
    const double k = 1.0 / sampleRate_Hz;
    const double hc = Membrane::gridSpacing(carry, k, kineticReserve(false), designReserve(false));
    const double allowed = carry.radius_m - 1.5 * hc;
    const double reach = std::hypot(0.5 * s.length_m, 0.5 * (s.count - 1) * s.spacing_m);
    if (reach > allowed && reach > 0.0)
    {
        const double shrink = std::max(0.0, allowed) / reach;
        s.length_m *= shrink;
        s.spacing_m *= shrink;
    }
    return s;
}

DrumConfig DrumConfig::lossless() const
{
    DrumConfig c = *this;
    c.batter.sigma0_per_s = 0.0;
    c.batter.sigma1_m2_per_s = 0.0;
    c.carry.sigma0_per_s = 0.0;
    c.carry.sigma1_m2_per_s = 0.0;
    c.snares.sigma0_per_s = 0.0;
    c.snares.sigma1_m2_per_s = 0.0;
    c.snares.contactDamping_s_per_m = 0.0;
    c.airBox.walls = AirWalls::reflecting;
    c.airBox.sigma_m = 0.0;
    for (RadiationChannelSpec* ch : { &c.outside.monopole, &c.outside.dipole, &c.outside.tiltSum, &c.outside.tiltDiff })
        ch->resistance = std::numeric_limits<double>::infinity();
    c.outside.nearFieldDamping = 0.0;
    return c;
}

namespace
{
// A head's share of kinetic energy kept for the explicit couplings at step k.
double reserveAt(const DrumConfig& c, bool ofBatter, double k)
{
    const MembraneSpec& head = ofBatter ? c.batter : c.carry;
    // the two bounds add (the cavity's already doubled for margin, OutsideAir.h's)
    const double air = c.cavity.model == AirModel::airbox ? 0.0 : OutsideAir::kineticReserve(c.outside, c.batter, c.carry, k, ofBatter);
    return Cavity::kineticReserve(c.cavity, head.radius_m, head.density_kg_per_m2, k) +
           CavityModes::kineticReserve(c.cavity, c.cavityModesUpTo_Hz(), head.radius_m, head.density_kg_per_m2, k) + air +
           NearFieldAir::kineticReserve(c.nearFieldSpec(), ofBatter);
}
} // namespace

double DrumConfig::kineticReserve(bool ofBatter) const { return reserveAt(*this, ofBatter, 1.0 / sampleRate_Hz); }

double DrumConfig::designReserve(bool ofBatter) const
{
    return reserveAt(*this, ofBatter, designStep(1.0 / sampleRate_Hz, (ofBatter ? batter : carry).gridTimeStep_s));
}

double DrumConfig::cavityModesUpTo_Hz() const
{
    if (cavity.model != AirModel::cavity)
        return 0.0;
    return cavity.modesUpTo_Hz;
}

DrumConfig::DrumConfig() : DrumConfig(mapParameters(ParameterSet {}, 48000.0))
{
    sampleRate_Hz = 48000.0; // the same grids at the 48 kHz step, heard at that rate
    outputRate_Hz = 0.0;
}

namespace
{
// mapParameters with the grids' coarseness given (qualityBandwidth_Hz's drums).
DrumConfig mapParametersAt(const ParameterSet& p, double sampleRate_Hz, double coarseness) noexcept
{
    DrumConfig c { DrumConfig::Unmapped {} };
    c.cavity.model = static_cast<AirModel>(std::lround(p.get(ParamId::airModel))); // none, cavity, airbox: the choices in order
    c.sampleRate_Hz = c.cavity.model == AirModel::airbox ? sampleRate_Hz : simulatedRateFor(sampleRate_Hz, coarseness).rate_Hz;
    c.outputRate_Hz = c.sampleRate_Hz == sampleRate_Hz ? 0.0 : sampleRate_Hz; // 0: the same
    // Damping sets the T60 of the heads' lowest modes (dampingT60); sigma0 = 3 ln(10) / T60
    // (the amplitude falls by 60 dB in T60).
    const double sigma0 = 3.0 * std::log(10.0) / dampingT60(p.get(ParamId::damping));
    const double sigma1 = p.get(ParamId::highDamping);

    c.batter.tension_N_per_m = p.get(ParamId::batterTension);
    c.batter.sigma0_per_s = sigma0;
    c.batter.sigma1_m2_per_s = sigma1;
    c.carry.tension_N_per_m = p.get(ParamId::carryFollows) >= 0.5
                                  ? std::clamp(p.get(ParamId::batterTension) *
                                                   (spec(ParamId::carryTension).defaultValue / spec(ParamId::batterTension).defaultValue),
                                               spec(ParamId::carryTension).minValue, spec(ParamId::carryTension).maxValue)
                                  : p.get(ParamId::carryTension);
    c.carry.sigma0_per_s = sigma0;
    c.carry.sigma1_m2_per_s = sigma1;
    // Grids designed for the largest values the controls allow: moving them changes coefficients only.
    for (MembraneSpec* m : { &c.batter, &c.carry })
    {
        m->gridSigma1_m2_per_s = spec(ParamId::highDamping).maxValue;
        m->gridCoarseness = coarseness;
        m->gridTimeStep_s = kGridDesignStep_s;
    }
    // Single precision for the batter alone: the carry head, which the snares strike, shifts
    // the buzz's mean spectrum in float (docs/MODEL.md, "Heads in single precision").
    c.batter.precision = p.get(ParamId::headPrecision) >= 0.5 ? HeadPrecision::single_precision : HeadPrecision::double_precision;
    c.carry.precision = HeadPrecision::double_precision;
    c.batter.gridTension_N_per_m = spec(ParamId::batterTension).maxValue;
    c.carry.gridTension_N_per_m = spec(ParamId::carryTension).maxValue;

    c.snares.tension_N = p.get(ParamId::snareTension);
    c.snares.gridTension_N = spec(ParamId::snareTension).maxValue;
    c.snares.gridCoarseness = coarseness;
    c.snares.gridTimeStep_s = kGridDesignStep_s;
    c.snares.engaged = p.get(ParamId::snaresEngaged) >= 0.5;
    c.snares.count = (int) std::lround(p.get(ParamId::snareCount));
    c.snares.scheme = p.get(ParamId::snareSolver) >= 0.5 ? CollisionScheme::newton : CollisionScheme::quadratised;
    c.snares.contactDamping_s_per_m = p.get(ParamId::snareDamping);
    c.snares.stiffness = p.get(ParamId::snareStiffness);
    c.cavity.shellDepth_m = p.get(ParamId::shellDepth);
    c.cavity.gridShellDepth_m = spec(ParamId::shellDepth).minValue;
    c.outside.enabled = p.get(ParamId::outsideAir) > 0.5;
    c.outside.nearField = p.get(ParamId::nearField) > 0.5;
    c.airBox.sigma_m = p.get(ParamId::airLoss);
    // ParamId::keepUp is the plug-in's: it lowers the bandwidth before the mapping.
    // ParamId::offlineAirBox is the host's, not the drum's: the plug-in reads it to choose the air
    // model of its offline renders (it arrives here as the air model).

    c.strikeRadius_frac = p.get(ParamId::strikePosition);
    c.strikeSpeedMax_m_per_s = p.get(ParamId::strikeSpeedMax);
    c.mallet.mass_kg = p.get(ParamId::malletMass);
    c.mallet.stiffness = p.get(ParamId::malletStiffness);
    c.mallet.exponent = p.get(ParamId::malletExponent);
    c.mallet.contactRadius_m = p.get(ParamId::malletContactRadius);

    c.mics.mixTop = p.get(ParamId::micTop);
    c.mics.mixBottom = p.get(ParamId::micBottom);
    c.mics.mixRoom = p.get(ParamId::micRoom);
    // The top mic's point off the snares' line (the x axis); the bottom mic's close to it.
    const double R = c.batter.radius_m, H = c.cavity.shellDepth_m;
    const double top = p.get(ParamId::micTopPosition) * R, bottom = p.get(ParamId::micBottomPosition) * R;
    c.mics.top = { top * std::cos(0.6), top * std::sin(0.6), 0.5 * H + p.get(ParamId::micTopHeight) };
    c.mics.bottom = { bottom * std::cos(0.14), bottom * std::sin(0.14), -0.5 * H - p.get(ParamId::micBottomHeight) };
    const double d = p.get(ParamId::micRoomDistance), angle = p.get(ParamId::micRoomAngle) * std::numbers::pi / 180.0;
    c.mics.room = { d * std::sin(angle), 0.0, 0.5 * H + d * std::cos(angle) };
    c.mics.reach_m = spec(ParamId::micRoomDistance).maxValue + spec(ParamId::shellDepth).maxValue; // any position of the schema
    c.outputGain = std::pow(10.0, p.get(ParamId::outputGain) / 20.0);
    c.room.reverberationTime_s = p.get(ParamId::roomTime);
    c.room.volume_m3 = p.get(ParamId::roomVolume);
    return c;
}
} // namespace

DrumConfig mapParameters(const ParameterSet& p, double sampleRate_Hz) noexcept
{
    return mapParametersAt(p, sampleRate_Hz, gridCoarsenessFor(p.get(ParamId::bandwidth)));
}

DrumConfig makeDrumConfig(const ParameterSet& p, double sampleRate_Hz)
{
    DrumConfig c = mapParameters(p, sampleRate_Hz);
    c.validate();
    return c;
}

double qualityBandwidth_Hz(double coarseness) noexcept
{
    if (! (coarseness >= 1.0))
        return std::isnan(coarseness) ? coarseness : qualityBandwidth_Hz(1.0);
    DrumConfig c = mapParametersAt(ParameterSet {}, 1.0 / kGridDesignStep_s, coarseness);
    c.sampleRate_Hz = 1.0 / kGridDesignStep_s; // the grids as designed, whatever rate simulates them
    const double k = kGridDesignStep_s;
    auto top = [&](double sine) { return std::asin(std::min(1.0, sine)) / (std::numbers::pi * k); };
    auto head = [&](const MembraneSpec& m, bool batter) {
        const double h = Membrane::gridSpacing(m, k, c.kineticReserve(batter));
        return top(std::sqrt(2.0) * k * std::sqrt(m.gridTension_N_per_m / m.density_kg_per_m2) / h);
    };
    const double wires =
        top(k * std::sqrt(c.snares.gridTension_N / c.snares.linearDensity_kg_per_m) / SnareWires::gridSpacing(c.snares, k));
    return std::min({ head(c.batter, true), head(c.carry, false), wires });
}

double gridCoarsenessFor(double bandwidth_Hz) noexcept
{
    static const double S = std::sin( // computed once, off the audio thread (by the first drum's build)
        std::numbers::pi * kGridDesignStep_s * qualityBandwidth_Hz(1.0));
    const double f = std::clamp(bandwidth_Hz, 1.0, 0.5 / kGridDesignStep_s);
    const double coarseness = std::round(1.0e6 * S / std::sin(std::numbers::pi * kGridDesignStep_s * f)) * 1.0e-6;
    return std::max(1.0, std::isfinite(coarseness) ? coarseness : 1.0);
}

double strikeSpeedFromVelocity(int midiVelocity, double maxSpeed_m_per_s)
{
    const int v = std::clamp(midiVelocity, 1, 127);
    return maxSpeed_m_per_s * std::pow(10.0, -1.6 * (127 - v) / 126.0);
}

} // namespace snaresim
