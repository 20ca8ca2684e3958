#pragma once
// Physical description of the drum model, in SI units. Built from a ParameterSet by
// makeDrumConfig() or filled in directly (tests). Validated by validate(), which throws
// std::invalid_argument with a readable message. The fields a parameter sets start at 0 here
// ("from the schema"): DrumConfig{} is the schema's default drum (Parameters.h) at 48 kHz,
// so there is one default drum.

#include "AirBox.h"
#include "Parameters.h"

#include <array>
#include <cmath>

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
    double density_kg_per_m2 = 0.353;   // rho_i: 10 mil PET batter
    double tension_N_per_m = 0.0;       // T_i (from the schema)
    double sigma0_per_s = 0.0;          // frequency-independent loss, 3 ln(10) / T60 (from the schema)
    double sigma1_m2_per_s = 0.0;       // frequency-dependent loss (from the schema)
    // The grid is chosen from eq. (39) for these (largest) values, so that moving the
    // tension or sigma1 below them changes coefficients only. Zero / negative: use the
    // actual tension / sigma1.
    double gridTension_N_per_m = 0.0;
    double gridSigma1_m2_per_s = -1.0;
    double gridCoarseness = 1.0;        // h = coarseness * h_min(eq. 39); >= 1 (from the schema)
    // The time step the coarseness is measured against where the step is longer: the grid is
    // then coarseness * h_min(this step), or h_min of the step where that is coarser (0: the
    // step itself). A grid so designed is the same at every rate below the design rate.
    double gridTimeStep_s = 0.0;
    HeadPrecision precision = HeadPrecision::double_precision; // from the schema; the air box runs double
};

// The spacing a grid of this coarseness is built with at step k, bound(step) being its
// stability bound (eq. 39 or 40) at a step: coarseness times the bound at the design step
// gridTimeStep_s where k is longer (0: k itself), never finer than the bound at k.
template <class Bound>
double designedSpacing(double coarseness, double k, double gridTimeStep_s, Bound bound)
{
    const double design = gridTimeStep_s > 0.0 && gridTimeStep_s < k ? gridTimeStep_s : k;
    const double asked = coarseness * bound(design), least = bound(k);
    return asked > least ? asked : least;
}

// A mallet: lumped mass with power-law contact, eq. (9)-(11).
// Every field from the schema.
struct MalletSpec
{
    double mass_kg = 0.0;
    double stiffness = 0.0;             // kappa_M, N / m^alpha
    double exponent = 0.0;              // alpha (1.5 Hertz ... 3 felt)
    double contactRadius_m = 0.0;       // support of g_b (raised cosine); below h: bilinear point
};

// The snare wires: N lossy strings under the carry head, eq. (12), colliding with it through
// the power-law potential of eq. (16), both ends attached to it (eq. 17-18).
// How the snare/carry-head collision of eq. (50) is solved each step.
enum class CollisionScheme
{
    newton,      // the paper's scheme: eq. (30) solved by Newton-Raphson (iterative)
    quadratised  // energy quadratisation: one linear solve per step (real time; see SnareContact.h)
};

struct SnareSpec
{
    int count = 0;                      // from the schema
    double length_m = 0.30;             // along a chord through the head
    double spacing_m = 0.004;           // between neighbouring wires
    double linearDensity_kg_per_m = 1.6e-3;
    double tension_N = 0.0;             // from the schema
    double sigma0_per_s = 8.0;          // wire losses
    double sigma1_m2_per_s = 2.0e-4;
    double gridTension_N = 0.0;         // design values of the wire grid, eq. (40) (0 / < 0: actual)
    double gridSigma1_m2_per_s = -1.0;
    double gridCoarseness = 1.0;        // h_s = coarseness * h_s,min(eq. 40); >= 1 (from the schema)
    double gridTimeStep_s = 0.0;        // as MembraneSpec::gridTimeStep_s
    double stiffness = 1.0e9;           // kappa_s, N/m per m^beta
    double exponent = 1.5;              // beta (1 ... 1.5; 1.5 is the Hertz exponent)
    bool engaged = true;                // false: thrown off, out of contact (from the schema)
    CollisionScheme scheme = CollisionScheme::newton; // from the schema
};

enum class AirModel
{
    none,   // heads uncoupled
    cavity, // uniform-pressure adiabatic cavity (Cavity.h)
    airbox  // the 3D air box around and inside the drum, heads embedded (eq. 5-8; DrumAir.h)
};

struct CavitySpec
{
    AirModel model = AirModel::cavity;  // from the schema
    double shellDepth_m = 0.0;          // H: V0 = pi R^2 H (from the schema)
    double gridShellDepth_m = 0.0;      // shallowest depth the grid allows (0: the depth itself)
    double airDensity_kg_per_m3 = 1.21;
    double soundSpeed_m_per_s = 343.0;
    // The enclosed air's own modes (CavityModes.h) up to this frequency, on the heads through
    // square cells of this size (0: the uniform pressure alone, the default). Not a parameter:
    // the outside air's channels are calibrated without them (docs/MODEL.md, "Cavity modes").
    double modesUpTo_Hz = 0.0;
    double modeCellSize_m = 0.02;
};

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
    bool enabled = false;                  // from the schema
    // scripts/calibrate_outside_air.py against the 1.4 m and 1.8 m air boxes (docs/MODEL.md)
    RadiationChannelSpec monopole { 1.311, 1.418e4 };  // V_b - V_c: the volume pushed out
    RadiationChannelSpec dipole { 1.294, 6.579e4 };    // V_b + V_c: the volume carried through
    RadiationChannelSpec tiltSum { 251.8, 3.185e7 };   // X_b + X_c: both heads' first moments together
    RadiationChannelSpec tiltDiff { 130.2, 4.488e7 };  // X_b - X_c: against each other
    double cornerLimit_Hz = 3000.0;        // the compliance 1/K behind each channel: sqrt(K/M) at most this
    double reserve = 0.05;                 // and at most this share of the lighter head's kinetic energy
    // The near field's mass on the heads' modes above (0,1) and (1,1) (NearFieldAir.h): those of
    // wavenumber j_mn / R up to this (rad/m; 0: none; 75: four 2 cm cells a wavelength), on at
    // most this share of each head's kinetic energy, with this share of the largest damper the
    // explicit coupling allows across each channel's compliance (0: lossless).
    bool nearField = true;                 // the near field with the channels (the schema's near_field)
    double nearFieldUpTo_per_m = 60.0;
    double nearFieldReserve = 0.08;
    double nearFieldDamping = 1.0;
    double nearFieldCellSize_m = 0.04;     // its shapes' cells: whole groups of the microphones' cells
};

// A point in the air, metres from the drum's centre (z up, the batter at z = +H/2).
struct AirPoint
{
    double x_m = 0.0, y_m = 0.0, z_m = 0.0;
};

// The air box of AirModel::airbox (density and sound speed from CavitySpec; the shell is rigid,
// its depth CavitySpec::shellDepth_m). Not a parameter: set by the config's owner.
struct DrumAirSpec
{
    // Box sides (x, y, z), centred on the drum. A side <= 0: the drum's extent plus twice margin_m.
    std::array<double, 3> size_m { 0.6, 0.6, 0.6 };
    double margin_m = 0.12;
    AirWalls walls = AirWalls::absorbing;
    double sigma_m = 0.0;                // sigma_a, eq. (5) (from the schema)
    double gridCoarseness = 1.0;         // h_a = coarseness * bound of eq. (41); >= 1
    int threads = 1;                     // AirBox::setThreads
    // Pressure microphones rho_a dt Psi; none given: airMicPoints() gives the defaults.
    static constexpr int maxMics = 8;
    std::array<AirPoint, maxMics> mics {};
    int numMics = 0;
};

// Microphones: the sound pressure at three points outside the drum (PressureMicrophones.h),
// metres from the drum's centre (z up, the batter at +H/2); from the schema.
struct MicSpec
{
    AirPoint top { 0.0, 0.0, 0.11 };     // above the batter
    AirPoint bottom { 0.0, 0.0, -0.11 }; // below the carry head, under the snares
    AirPoint room { 0.0, 0.0, 1.07 };    // the room
    double reach_m = 2.5;                // no microphone farther from the centre (the delay lines' length)
    double cellSize_m = 0.02;            // side of the heads' radiating cells
    double fineCellSize_m = 0.008;       // and of those within three cells of a microphone's foot
    double topGain = 5.7e-3;             // output per Pa
    double bottomGain = 3.7e-3;          // output per Pa
    double farGain = 0.041;              // output per Pa (the room)
    double mixTop = 0.0, mixBottom = 0.0, mixFar = 0.0; // weights of the mixed output (from the schema)
};

struct DrumConfig
{
    // The schema's default drum at 48 kHz: mapParameters(ParameterSet {}, 48000).
    DrumConfig();
    // The constants alone, every field a parameter sets at 0: what mapParameters fills in.
    struct Unmapped {};
    explicit DrumConfig(Unmapped) {}

    double sampleRate_Hz = 48000.0;     // the simulation's rate: the time step k = 1 / rate
    // The host's rate, a power-of-two multiple of sampleRate_Hz (HostRateInterpolator.h);
    // 0: the same.
    double outputRate_Hz = 0.0;
    double outputRate() const { return outputRate_Hz > 0.0 ? outputRate_Hz : sampleRate_Hz; }
    int outputFactor() const { return (int) std::lround(outputRate() / sampleRate_Hz); }
    MembraneSpec batter;
    MembraneSpec carry { .radius_m = 0.1778, .density_kg_per_m2 = 0.106 }; // 3 mil PET
    SnareSpec snares;
    CavitySpec cavity;
    DrumAirSpec air;                    // used when cavity.model == AirModel::airbox
    OutsideAirSpec outside;             // with the cavity or no air, not in the air box
    MicSpec mics;
    MalletSpec mallet;
    int numMallets = 4;                 // independent mallets for flams and rolls
    double strikeSpeedMax_m_per_s = 0.0;// MIDI velocity 127 (from the schema)
    double strikeRadius_frac = 0.0;     // default strike point, fraction of R from the centre (from the schema)
    double outputGain = 0.0;            // scales the mixed output (from the schema)

    // Throws std::invalid_argument when a value is out of physical range or when the
    // grid the scheme needs cannot be built.
    void validate() const;

    // Share of a head's kinetic energy kept in its grid for the explicit couplings (the cavity,
    // the outside air): Membrane's kineticReserve.
    double kineticReserve(bool ofBatter) const;
    // The cavity's modes up to this frequency (CavityModes.h): CavitySpec::modesUpTo_Hz with the
    // reduced cavity, none in the air box or without air.
    double cavityModesUpTo_Hz() const;

    // All losses off (sigma0 = sigma1 = 0, the air box's walls reflecting and sigma_a = 0,
    // the outside air's resistances open, the near field's dampers off):
    // the energy is then conserved to round-off.
    DrumConfig lossless() const;

    // The snare wires as simulated: on a coarse carry-head grid (low sample rates, coarse
    // quality) their band is shrunk, length and spacing alike, until every wire end has a
    // head node at least 1.5 h_c inside the rim.
    SnareSpec fittedSnares() const;

    // The air box of AirModel::airbox: its size resolved, the rigid shell with closed ends
    // (the heads replace the discs).
    AirBoxSpec airBoxSpec() const;
    // The air microphones: air.mics, or when none is given the drum's top, bottom and room
    // microphones (MicSpec), each clamped inside the box, a cell and a half from its walls.
    int airMicPoints(std::array<AirPoint, DrumAirSpec::maxMics>& out) const;
};

// Map the user-facing parameters onto the physical description, validated (throws
// std::invalid_argument when the model cannot run at this sample rate and quality). The drum
// is simulated at physicsRateFor(sampleRate_Hz) and heard at sampleRate_Hz (outputRate_Hz),
// but in the air box, which is simulated at the host's rate.
DrumConfig makeDrumConfig(const ParameterSet& params, double sampleRate_Hz);

// The same mapping without validation and without allocating: for the audio thread, where
// the values come from a ParameterSet (always in range) and only live-changeable fields are
// taken from the result (Drum::applyLive).
DrumConfig mapParameters(const ParameterSet& params, double sampleRate_Hz) noexcept;

// What a grid coarseness (the spacing as a multiple of the stability bound, eq. 39 and 40)
// carries: the highest frequency of the heads' and the wires' grids as the schema's default
// drum builds them at 48 kHz (their design rate), each at its highest tension: for a head
// sin(pi f k) = sqrt(2) k c / h (the 5-point Laplacian's top mode, eq. 39's scheme), for the
// wires sin(pi f k) = k c_s / h_s; the lowest of the three. Coarseness 1 carries about 21 kHz,
// 2 about 7.8 kHz, 4 about 3.8 kHz.
double qualityBandwidth_Hz(double coarseness) noexcept;
// Its inverse, the grids' coarseness for the Quality parameter's bandwidth: every spacing is
// proportional to the coarseness, so sin(pi f k) = S / coarseness with S that of coarseness 1.
// At least 1 (the stability bound); taken to a millionth, so a bandwidth read from
// qualityBandwidth_Hz gives its coarseness exactly.
double gridCoarsenessFor(double bandwidth_Hz) noexcept;

// Documented MIDI velocity curve: speed = maxSpeed * 10^(-1.6 (127 - v) / 126), v in 1..127,
// so 127 -> maxSpeed and 1 -> maxSpeed / 40 (about 32 dB of strike speed).
double strikeSpeedFromVelocity(int midiVelocity, double maxSpeed_m_per_s);

} // namespace snaresim
