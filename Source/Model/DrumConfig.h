#pragma once
// Physical description of the drum model, in SI units. Built from a ParameterSet by
// makeDrumConfig() or filled in directly (tests). Validated by validate(), which throws
// std::invalid_argument with a readable message. The fields a parameter sets start at 0 here
// ("from the schema"): DrumConfig{} is the schema's default drum (Parameters.h) at 48 kHz,
// so there is one default drum.

#include "AirPoint.h"
#include "CavitySpec.h"
#include "DrumAirSpec.h"
#include "MalletSpec.h"
#include "MembraneSpec.h"
#include "MicSpec.h"
#include "NearFieldSpec.h"
#include "OutsideAirSpec.h"
#include "Parameters.h"
#include "RoomSpec.h"
#include "SnareSpec.h"

#include <array>
#include <cmath>

namespace snaresim
{

struct DrumConfig
{
    // The schema's default drum simulated at 48 kHz and heard at that rate: the grids of
    // mapParameters(ParameterSet {}, 48000), which simulates them at 32 kHz. The physics' tests
    // and the lab start from it.
    DrumConfig();
    // The constants alone, every field a parameter sets at 0: what mapParameters fills in.
    struct Unmapped
    {};
    explicit DrumConfig(Unmapped) {}

    double sampleRate_Hz = 48000.0; // the simulation's rate: the time step k = 1 / rate
    // The host's rate, sampleRate_Hz times L / M (simulatedRateFor, HostRateInterpolator.h);
    // 0: the same.
    double outputRate_Hz = 0.0;
    double outputRate() const { return outputRate_Hz > 0.0 ? outputRate_Hz : sampleRate_Hz; }
    // L / M, the host's rate over the simulated one in lowest terms (M 1, 2 or 3)
    int outputDown() const
    {
        const double r = outputRate() / sampleRate_Hz;
        for (int m = 1; m < 3; ++m)
            if (std::abs(r * m - std::round(r * m)) <= 1e-9 * r * m)
                return m;
        return 3;
    }
    int outputUp() const { return (int) std::lround(outputRate() / sampleRate_Hz * outputDown()); }
    MembraneSpec batter;
    MembraneSpec carry { .radius_m = 0.1778, .density_kg_per_m2 = 0.106 }; // 3 mil PET
    SnareSpec snares;
    CavitySpec cavity;
    DrumAirSpec airBox;     // used when cavity.model == AirModel::airbox
    OutsideAirSpec outside; // with the cavity or no air, not in the air box
    MicSpec mics;
    RoomSpec room; // the room the microphones hear (DiffuseRoom.h)
    MalletSpec mallet;
    int numMallets = 4;                  // independent mallets for flams and rolls
    double strikeSpeedMax_m_per_s = 0.0; // MIDI velocity 127 (from the schema)
    double strikeRadius_frac = 0.0;      // default strike point, fraction of R from the centre (from the schema)
    double outputGain = 0.0;             // scales the mixed output (from the schema)

    // Throws std::invalid_argument when a value is out of physical range or when the
    // grid the scheme needs cannot be built.
    void validate() const;

    // Share of a head's kinetic energy kept in its grid for the explicit couplings (the cavity,
    // the outside air): Membrane's kineticReserve.
    double kineticReserve(bool ofBatter) const;
    // That share at the step the heads' grids are designed for (MembraneSpec::gridTimeStep_s,
    // where it is shorter than the simulated step; else the simulated step), so that a drum
    // simulated at a lower rate keeps the design step's grid (Membrane::gridSpacing).
    double designReserve(bool ofBatter) const;
    // The cavity's modes up to this frequency (CavityModes.h): CavitySpec::modesUpTo_Hz with the
    // reduced cavity, none in the air box or without air.
    double cavityModesUpTo_Hz() const;
    // What the near field is built from (NearFieldAir.h).
    NearFieldSpec nearFieldSpec() const { return { outside, cavity, batter, carry, cavityModesUpTo_Hz() }; }

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
    // The air microphones: airBox.mics, or when none is given the drum's top, bottom and room
    // microphones (MicSpec), each clamped inside the box, a cell and a half from its walls.
    int airMicPoints(std::array<AirPoint, DrumAirSpec::maxMics>& out) const;
};

// Map the user-facing parameters onto the physical description, validated (throws
// std::invalid_argument when the model cannot run at this sample rate and quality). The drum
// is simulated at simulatedRateFor(sampleRate_Hz, the grids' coarseness) and heard at
// sampleRate_Hz (outputRate_Hz), but in the air box, which is simulated at the host's rate.
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
