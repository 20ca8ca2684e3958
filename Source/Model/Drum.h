#pragma once
// The assembled model (eq. 1-50; the air as the reduced cavity with the outside air's channels,
// or the air box, DrumAir.h), in the paper's terms: components, each with its own state, free
// update and energy (the batter and carry Membranes, the SnareWires, the Mallets, the Cavity,
// the OutsideAir, the CavityModes, the NearFieldAir, the air box), and couplings, each with its
// own forces, solve and energy (MalletContact, SnareContact with the attached ends,
// CavityCoupling, OutsideAirCoupling, CavityModesCoupling, NearFieldCoupling, the air box's
// HeadEmbeddings); the PressureMicrophones listen. The parts in contact with a head (the mallets,
// the snares: HeadContact.h) and the air attached to the heads explicitly (the cavity's modes, the
// outside air, the near field: AttachedAir.h) are two lists; the heads, the cavity and the air
// box are written out. step() runs them in a fixed order;
// energyTerms() lists which of them each ledger term sums. Clients play it through a
// DrumSession (Source/Player).

#include "Articulations.h"
#include "AttachedAir.h"
#include "AttachedCavityModes.h"
#include "AttachedNearField.h"
#include "AttachedOutsideAir.h"
#include "Attachments.h"
#include "Cavity.h"
#include "CavityCoupling.h"
#include "DiffuseRoom.h"
#include "DrumAir.h"
#include "DrumConfig.h"
#include "DrumSnapshot.h"
#include "EnergyLedger.h"
#include "HeadContact.h"
#include "HostRateInterpolator.h"
#include "MalletsOnBatter.h"
#include "Membrane.h"
#include "PressureMicrophones.h"
#include "SnaresOnCarry.h"
#include "StepProfile.h"

#include <array>
#include <vector>

namespace snaresim
{

struct SolverStats
{
    int lastIterations = 0;             // Newton iterations of the last step that solved a contact
    int maxIterations = 0;              // since the last resetStats(), mallets and snares
    int maxSnareIterations = 0;         // the snare solve alone (largest over its node groups)
    long fallbacks = 0;                 // steps where a Newton solve missed its cap and fell back
    int snareContacts = 0;              // snare points touching the carry head after the last step
    double maxSnarePenetration_m = 0.0; // largest xi since resetStats()
    int maxAirTrials = 0;               // air box: most contact trials of one head's joint solve (DrumAir.h)
    long airCapped = 0;                 // air box: joint solves stopped at their cap
    long airTrials = 0;                 // air box: contact trials of both heads since resetStats()
    double maxAirMismatch = 0.0;        // air box: largest final mismatch of a joint solve, relative to max |w|
};

enum class Mic
{
    top,    // the sound pressure above the batter
    bottom, // below the carry head (snare side)
    room,   // at the room microphone
    mix     // the weighted mix that step() returns
};

// Signals of one step: the sound pressure at the microphones (MicSpec: PressureMicrophones.h;
// in the air box, the box's own pressure there when its microphones are the drum's), and the mix.
struct MicSignals
{
    double top_Pa = 0.0;
    double bottom_Pa = 0.0;
    double room_Pa = 0.0;
    double mix = 0.0; // the output sample
};

class Drum
{
public:
    // Throws std::invalid_argument (readable message) when the config cannot be simulated.
    explicit Drum(const DrumConfig& config);
    Drum(const Drum&) = delete; // the couplings hold references to the components
    Drum& operator=(const Drum&) = delete;

    const DrumConfig& config() const { return cfg; }
    // the host's rate, at which step() and process() play (config().outputRate())
    double sampleRate() const { return cfg.outputRate(); }
    // the rate the physics is simulated at (config().sampleRate_Hz; HostRateInterpolator.h)
    double simulationRate() const { return cfg.sampleRate_Hz; }
    // What the signals at the host's rate lag the simulation by, in host samples: the
    // interpolator's delay (96 at 48 kHz and 85.7 at 44.1 kHz for grids simulated at 32 and
    // 33.075 kHz; 0 where the drum is simulated at the host's rate).
    double latencySamples() const { return (double) toHost.delay() / (double) toHost.down(); }

    // Start a strike with the next free mallet (round robin): speed in m/s (> 0, downward),
    // position as fractions of the radius. Real-time safe.
    void strike(double speed_m_per_s, double x_frac, double y_frac);
    // A strike where the main strike lands (mainStrike(), Articulations.h): the strike_position
    // control's radius, at its angle from the snares.
    void strikeAtDefaultPoint(double speed_m_per_s);

    // Play a MIDI note with its articulation (Articulations.h): velocity 1..127 through the
    // velocity curve, or snares off / on. Real-time safe.
    void playNote(int midiNote, int velocity);

    // Takes a config's coefficients (tensions, losses, contact laws, mallet, microphones, gains,
    // air, snares on/off) without touching the grids; real-time safe. `next` comes from the
    // parameters whose change needs only coefficients (ChangeNeeds, Parameters.h); what else
    // differs is ignored, and each component keeps its coefficients within what its grid was
    // built for (eq. 39, 40), so the scheme stays stable whatever it is given.
    void applyLive(const DrumConfig& next) noexcept;

    // Snares on the carry head or thrown off. Real-time safe.
    void setSnaresEngaged(bool engaged);
    bool snaresEngaged() const { return engaged; }

    // Advance one sample of the host's rate and return the mixed output sample: a step of the
    // simulation where one is due (M in L host samples: HostRateInterpolator.h), the signals
    // interpolated.
    double step();
    // the last simulated step's signals (at the simulation's rate)
    const MicSignals& lastSignals() const { return signals; }
    // The last host sample's signal of one microphone at audio level (its gain and the output
    // gain applied); Mic::mix is what step() returned.
    double output(Mic mic) const;

    // Render n samples of the mix (overwrites out). Real-time safe.
    void process(float* out, int n);

    // Energy bookkeeping, computed every step while enabled (costs about one extra pass): one
    // term per entry of energyTerms() (batter, carry, mallets, snares, cavity, then the air's
    // terms in play: the default drum's outside), in that order.
    void setEnergyTracking(bool on) { trackEnergy = on; }
    bool energyTracking() const noexcept { return trackEnergy; }
    const EnergyLedger& energy() const { return ledger; }

    const SolverStats& solverStats() const { return stats; }
    void resetStats() { stats = {}; }

    // Where the steps' time goes (StepProfile.h), off by default. While on, step() reads the
    // clock between its phases; on or off it plays the same numbers and allocates nothing.
    void setProfiling(bool on) { profiling = on; }
    bool isProfiling() const { return profiling; }
    const StepProfile& profile() const { return stepProfile; }
    void resetProfile() { stepProfile.clear(); }

    // Silence the drum and park the mallets.
    void reset();

    const Membrane& batter() const { return batterHead; }
    const Membrane& carry() const { return carryHead; }
    const SnareWires& snareWires() const { return wires; }
    const SnareContact& snareContact() const { return snareCoupling; }
    SnareContact& snareContact() { return snareCoupling; }
    const Cavity& cavity() const { return cavityAir; }
    const OutsideAir& outsideAir() const { return attachedAir.get<AttachedOutsideAir>().component(); }
    const CavityModes& cavityModes() const { return attachedAir.get<AttachedCavityModes>().component(); }
    const NearFieldAir& nearFieldAir() const { return attachedAir.get<AttachedNearField>().component(); }
    // The air box (AirModel::airbox): active() false otherwise.
    const DrumAir& airBox() const { return boxAir; }
    const PressureMicrophones& microphones() const { return pressureMics; }
    // The air microphones' pressure rho_a dt+ Psi (Pa) at the last step (air box only; 0 mics otherwise).
    int numAirMics() const { return boxAir.active() ? boxAir.numMics() : 0; }
    double airMicPressure(int i) const { return boxAir.micPressure(i); }
    const Mallet& mallet(int i) const { return mallets[(size_t) i]; }
    bool isFinite() const;

    // Fill a display snapshot of the current state. Real-time safe (no allocation); costs
    // about a thousand samples' worth of reads, so call it at screen rate, not per sample.
    void fillSnapshot(DrumSnapshot& out) const noexcept;
    int numMallets() const { return (int) mallets.size(); }

private:
    // A strike as an articulation places it (its radius, or the strike_position control's; its
    // angle and speed scale), at this speed before the scale.
    void strikeAs(const Articulation& a, double speed_m_per_s);
    auto energyTerms() const; // the ledger's terms and their owners (Drum.cpp)
    void updateEnergy();
    double simulate(); // one step of the simulation
    template <class Lap>
    double stepWith(Lap& lap); // simulate(), lap(phase) after each phase (Drum.cpp)
    template <class Lap>
    void stepCouplings(Lap& lap); // steps 1-2 of step() (free updates, couplings)
    template <class Lap>
    void stepCouplingsInAir(Lap& lap); // the same with the air box
    void noteSolves(const ContactSolves& solves);
    void retrieveRisingMallets();
    void placeAirMics(const DrumConfig& c); // the air box's microphones (DrumConfig::airMicPoints)

    static constexpr double kRetrieveHeight_m = 0.01; // rising mallets are taken back 1 cm above the head

    DrumConfig cfg;
    double k;
    // Components and the couplings between them (each coupling after what it couples).
    Cavity cavityAir;               // component: the enclosed air as one pressure
    Membrane batterHead, carryHead; // components
    // The parts in contact with a head, each a component with its contact coupling (HeadContact.h),
    // built, stepped and listed in the ledger in this order.
    Attachments<MalletsOnBatter, SnaresOnCarry> contacts;
    std::vector<Mallet>& mallets;  // the contacts' own: never resized after construction
    SnareWires& wires;             // component
    SnareContact& snareCoupling;   // coupling: wires - carry head
    bool& engaged;                 // the snares on the carry head
    CavityCoupling cavityCoupling; // coupling: heads - cavity
    // The air models attached to the heads explicitly, each a component with its coupling
    // (AttachedAir.h), built, stepped and listed in the ledger in this order; inactive ones are skipped.
    Attachments<AttachedCavityModes, AttachedOutsideAir, AttachedNearField> attachedAir;
    DrumAir boxAir; // component (the air box) with its couplings to the heads; inactive without

    PressureMicrophones pressureMics; // the microphones: a listener, no energy, no force
    DiffuseRoom room;                 // the room's diffuse field at them: a listener too
    HostRateInterpolator toHost;      // the signals at the host's rate
    int hostPhase = 0, lastPhase = 0; // of the next and the last host sample, 0 .. L - 1
    EnergyLedger ledger;
    int malletsTerm = -1, snaresTerm = -1; // the ledger terms a strike and the snares switch change
    SolverStats stats;
    MicSignals signals;
    bool trackEnergy = false;
    bool profiling = false;
    StepProfile stepProfile;
    int nextMallet = 0;
    long long samplesRendered = 0;
};

} // namespace snaresim
