#include "Drum.h"

#include "EnergyTerm.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <type_traits>

namespace snaresim
{

namespace
{
// The config as the drum runs it: validated, and the heads in double precision in the air box
// (its embedding updates them with the air in double, HeadEmbedding).
DrumConfig validated(const DrumConfig& c)
{
    c.validate();
    DrumConfig run = c;
    if (run.cavity.model == AirModel::airbox)
        run.batter.precision = run.carry.precision = HeadPrecision::double_precision;
    return run;
}

// step()'s clock: lap(phase) adds the time since the last lap (or the step's start) to the
// phase. The one that is off compiles to nothing.
template <bool On>
struct PhaseClock
{
    explicit PhaseClock(StepProfile&) {}
    void operator()(StepPhase) {}
};

template <>
struct PhaseClock<true>
{
    using Clock = std::chrono::steady_clock;
    StepProfile& profile;
    Clock::time_point last;

    explicit PhaseClock(StepProfile& p) : profile(p), last(Clock::now()) { ++profile.steps; }
    void operator()(StepPhase phase)
    {
        const auto now = Clock::now();
        profile.seconds[(size_t) phase] += std::chrono::duration<double>(now - last).count();
        last = now;
    }
};

} // namespace

// The ledger's terms in column order, eq. (34): H = H_b + H_c + H_M + H_s + the air's, each
// the sum of its owners' energies (and step losses) in the order listed. A new component or
// coupling that stores energy adds its term here. (CavityCoupling stores none: no term lists it.)
auto Drum::energyTerms() const
{
    return std::tuple_cat(std::tuple { EnergyTerm("batter", batterHead),                          // eq. (35)
                                       EnergyTerm("carry", carryHead) },                          // eq. (35)
                          contacts.energyTerms(),                                                 // the mallets (37), the snares (38)
                          std::tuple { EnergyTerm("cavity", cavityAir) },                         // (K/2) dV^{n+1} dV^n
                          attachedAir.energyTerms(),                                              // AttachedAir.h
                          std::tuple { EnergyTerm("airbox", boxAir).listedIf(boxAir.active()) }); // eq. (36)
}

Drum::Drum(const DrumConfig& config)
    : cfg(validated(config)), k(1.0 / config.sampleRate_Hz), cavityAir(cfg.cavity, cfg.batter.radius_m),
      batterHead(cfg.batter, k, cfg.kineticReserve(true), cfg.designReserve(true)),
      carryHead(cfg.carry, k, cfg.kineticReserve(false), cfg.designReserve(false)), contacts(cfg, batterHead, carryHead, k),
      mallets(contacts.get<MalletsOnBatter>().mallets), wires(contacts.get<SnaresOnCarry>().wires),
      snareCoupling(contacts.get<SnaresOnCarry>().coupling), engaged(contacts.get<SnaresOnCarry>().engaged),
      cavityCoupling(batterHead, carryHead, cavityAir), attachedAir(cfg, batterHead, carryHead, k),
      pressureMics(cfg.mics, cfg.cavity, cfg.sampleRate_Hz, batterHead, carryHead), room(cfg.room, cfg.sampleRate_Hz),
      toHost(cfg.outputUp(), cfg.outputDown())
{
    // the float heads' volumes and moments taken with the microphones' cells
    batterHead.takeSumsWithBlocks(pressureMics.cellSide(0));
    carryHead.takeSumsWithBlocks(pressureMics.cellSide(1));
    if (cfg.cavity.model == AirModel::airbox)
    {
        boxAir.build(cfg.airBoxSpec(), cfg.airBox.threads, cfg.cavity.shellDepth_m, k, batterHead, carryHead);
        placeAirMics(cfg);
        stepProfile.path = StepPath::airBox;
    }
    const auto terms = energyTerms();
    registerTerms(ledger, terms);
    malletsTerm = termOwning(terms, mallets);
    snaresTerm = termOwning(terms, wires);
}

void Drum::placeAirMics(const DrumConfig& c)
{
    std::array<AirPoint, DrumAirSpec::maxMics> points {};
    const int count = c.airMicPoints(points);
    boxAir.placeMics(points, count);
}

void Drum::strike(double speed, double xFrac, double yFrac)
{
    if (! std::isfinite(speed) || ! std::isfinite(xFrac) || ! std::isfinite(yFrac) || speed <= 0.0)
        return;
    speed = std::min(speed, 50.0);
    const double r = std::hypot(xFrac, yFrac);
    if (r > 0.95) // keep the patch on the head
    {
        xFrac *= 0.95 / r;
        yFrac *= 0.95 / r;
    }

    // Round robin, skipping a mallet that is still touching the head when another is free.
    int chosen = nextMallet;
    for (int tries = 0; tries < (int) mallets.size(); ++tries)
    {
        const int i = (nextMallet + tries) % (int) mallets.size();
        const Mallet& m = mallets[(size_t) i];
        if (! m.inPlay() || (m.etaNow <= 0.0 && m.etaPrev <= 0.0))
        {
            chosen = i;
            break;
        }
    }
    nextMallet = (chosen + 1) % (int) mallets.size();

    // The mallet's energy with its contact potential at n-1/2 (eq. 37): what the strike replaces.
    Mallet& m = mallets[(size_t) chosen];
    auto held = [](const Mallet& ml) { return ml.energyBeforeStep() + MalletContact::potentialEnergyBeforeStep(ml); };
    const double before = held(m);
    const double R = cfg.batter.radius_m;
    double after = 0.0;
    if (m.aim(xFrac * R, yFrac * R))
    {
        m.launch(batterHead.sampleNow(m.patch()), batterHead.samplePrev(m.patch()), speed);
        after = held(m);
    }
    ledger.injected_J += after - before;
    ledger.change(malletsTerm, after - before);
}

void Drum::strikeAs(const Articulation& a, double speed)
{
    const double r = a.radius_frac < 0.0 ? cfg.strikeRadius_frac : a.radius_frac;
    strike(a.speedScale * speed, r * std::cos(a.angle_rad), r * std::sin(a.angle_rad));
}

void Drum::strikeAtDefaultPoint(double speed) { strikeAs(mainStrike(), speed); }

void Drum::playNote(int note, int velocity)
{
    const Articulation& a = articulationForNote(note);
    switch (a.action)
    {
        case ArticulationAction::snaresOff: setSnaresEngaged(false); return;
        case ArticulationAction::snaresOn: setSnaresEngaged(true); return;
        case ArticulationAction::strike: break;
    }
    strikeAs(a, strikeSpeedFromVelocity(velocity, cfg.strikeSpeedMax_m_per_s));
}

void Drum::applyLive(const DrumConfig& next) noexcept
{
    // The air box keeps its model and box (its grid); the rest as for the other models.
    DrumConfig kept { DrumConfig::Unmapped {} };
    if (boxAir.active())
    {
        kept = next;
        kept.cavity.model = AirModel::airbox;
        kept.airBox = cfg.airBox;
    }
    const DrumConfig& n = boxAir.active() ? kept : next;
    const double gains[2] = { batterHead.forceGain(), carryHead.forceGain() };
    batterHead.setCoefficients(n.batter.tension_N_per_m, n.batter.sigma0_per_s, n.batter.sigma1_m2_per_s);
    carryHead.setCoefficients(n.carry.tension_N_per_m, n.carry.sigma0_per_s, n.carry.sigma1_m2_per_s);
    if (boxAir.active() && (gains[0] != batterHead.forceGain() || gains[1] != carryHead.forceGain()))
        boxAir.refresh(); // the embeddings' gains and the heads' response to forces (allocates nothing)
    wires.setCoefficients(n.snares.tension_N, n.snares.sigma0_per_s, n.snares.sigma1_m2_per_s);
    snareCoupling.setLaw(n.snares.stiffness, n.snares.exponent, n.snares.contactDamping_s_per_m);
    cavityAir.setSpec(n.cavity, n.batter.radius_m);
    attachedAir.each([&](auto& air) { air.setSpec(n); });
    if (n.room != cfg.room)
        room.setSpec(n.room); // runs the network's first passes: only when the room changes
    for (auto& m : mallets)
        m.setSpec(n.mallet); // a mallet in flight keeps its position; its patch changes at the next strike
    auto moved = [](const AirPoint& a, const AirPoint& b) { return a.x_m != b.x_m || a.y_m != b.y_m || a.z_m != b.z_m; };
    if (moved(n.mics.top, cfg.mics.top) || moved(n.mics.bottom, cfg.mics.bottom) || moved(n.mics.room, cfg.mics.room) ||
        n.cavity.shellDepth_m != cfg.cavity.shellDepth_m)
    {
        pressureMics.setPositions(n.mics, n.cavity.shellDepth_m); // a delay beyond the lines' length is held at it
        if (boxAir.active())
            placeAirMics(n);
    }
    const HeadPrecision heads[2] = { cfg.batter.precision, cfg.carry.precision }; // the grids' own
    const OutsideAirSpec outsideSpec = cfg.outside;                               // the model's own, like the grids
    const double modesUpTo = cfg.cavity.modesUpTo_Hz, modeCells = cfg.cavity.modeCellSize_m;
    cfg = n;
    cfg.cavity.modesUpTo_Hz = modesUpTo;
    cfg.cavity.modeCellSize_m = modeCells;
    cfg.batter.precision = heads[0];
    cfg.carry.precision = heads[1];
    cfg.outside = outsideSpec;
    setSnaresEngaged(n.snares.engaged);
}

void Drum::fillSnapshot(DrumSnapshot& out) const noexcept
{
    constexpr int P = DrumSnapshot::raster;
    const double R = cfg.batter.radius_m;
    float peak = 0.0f;
    auto sampleHead = [&](const Membrane& head, std::array<float, P * P>& dst) {
        const auto& grid = head.grid();
        for (int j = 0; j < P; ++j)
            for (int i = 0; i < P; ++i)
            {
                const double x = ((i + 0.5) / P * 2.0 - 1.0) * R, y = ((j + 0.5) / P * 2.0 - 1.0) * R;
                const int node = grid.nearestInterior(x, y);
                const float v = node >= 0 ? (float) head.nowAt(node) : 0.0f;
                dst[(size_t) (j * P + i)] = v;
                out.onHead[(size_t) (j * P + i)] = node >= 0 ? 1 : 0;
                peak = std::max(peak, std::abs(v));
            }
    };
    sampleHead(batterHead, out.batter);
    sampleHead(carryHead, out.carry);

    constexpr int Q = DrumSnapshot::wirePoints;
    out.numWires = std::min(wires.count(), DrumSnapshot::maxWires);
    out.snaresEngaged = engaged;
    const int M = wires.intervals();
    out.wireLength_frac = (float) (M * wires.spacing() / (2.0 * R));
    for (int i = 0; i < out.numWires; ++i)
    {
        out.wireY_frac[(size_t) i] = (float) (wires.wireY(i) / R);
        for (int q = 0; q < Q; ++q)
        {
            const int l = (int) std::lround((double) q / (Q - 1) * M);
            const size_t slot = (size_t) (i * Q + q);
            out.wire[slot] = engaged ? (float) wires.uNow[(size_t) (i * (M + 1) + l)] : 0.0f;
            const bool interior = l > 0 && l < M;
            out.touching[slot] = engaged && interior && snareCoupling.gapAt(i, l) > 0.0 ? 1 : 0;
        }
    }
    out.peakDisplacement = peak;
    out.samplesRendered = samplesRendered;
}

bool Drum::isFinite() const
{
    return batterHead.isFinite() && carryHead.isFinite() && (! engaged || wires.isFinite()) && std::isfinite(signals.mix);
}

void Drum::setSnaresEngaged(bool on)
{
    if (on == engaged)
        return;
    const double before = wires.energyBeforeStep() + snareCoupling.energyBeforeStep();
    if (on)
        snareCoupling.layOnHead(); // wires rest on the head as it moves now
    else
    {
        wires.clear(); // thrown off: out of the model
        snareCoupling.clear();
    }
    engaged = on;
    const double after = on ? wires.energyBeforeStep() : 0.0;
    ledger.injected_J += after - before;
    ledger.change(snaresTerm, after - before);
}

// Out of line (also stepCouplingsInAir): step() without the profile then compiles as it did
// before the profile existed (the same inlining, the same instructions).
template <class Lap>
[[gnu::noinline]] void Drum::stepCouplings(Lap& lap)
{
    // 1. The components' free updates, with the cavity's and the outside air's pressures at
    //    time n on the heads (explicit, CavityCoupling.h, OutsideAirCoupling.h).
    HeadPressure b, c; // the attached air's uniform and tilt parts (the outside air's), 0 without
    attachedAir.each([&](auto& air) {
        if (air.active())
            air.beforeHeads(b, c); // the cavity's modes and the near field on the heads' cells
    });
    // 2. The couplings: each solves for its forces and adds them to the free updates. Steps 1
    //    and 2 run head by head: a head's free update, then the components acting on it alone
    //    and their contacts (no contact joins the two heads within a step), so that the
    //    batter's sums are taken while its state is in cache.
    ContactSolves solves;
    auto onHead = [&](auto head) { // the contacts on this head: their free updates, then their solves
        contacts.each([&](auto& contact) {
            if constexpr (std::decay_t<decltype(contact)>::head == std::decay_t<decltype(head)>::value)
                contact.computeFree(lap); // the mallets (eq. 43), the wires (eq. 28)
        });
        contacts.each([&](auto& contact) {
            if constexpr (std::decay_t<decltype(contact)>::head == std::decay_t<decltype(head)>::value)
            {
                contact.solve(solves); // eq. (44)-(45), (48)-(50)
                contact.lapSolve(lap);
            }
        });
    };
    batterHead.computeFree(cavityCoupling.pressureOnBatter() + b.p0, b.px, b.py); // eq. (22) without the contact force
    lap(StepPhase::batterFree);
    onHead(std::integral_constant<int, 0> {});
    batterHead.takeSumsNow();
    lap(StepPhase::batterFree);
    carryHead.computeFree(cavityCoupling.pressureOnCarry() + c.p0, c.px, c.py); // eq. (23) without snare and end forces
    lap(StepPhase::carryFree);
    onHead(std::integral_constant<int, 1> {});
    noteSolves(solves);
}

void Drum::noteSolves(const ContactSolves& solves)
{
    int iterations = solves.mallets.iterations;
    bool fallback = solves.mallets.fallback;
    if (solves.snaresSolved)
    {
        const auto& snare = solves.snares;
        iterations = std::max(iterations, snare.iterations);
        fallback = fallback || snare.fallback;
        stats.maxSnareIterations = std::max(stats.maxSnareIterations, snare.iterations);
        stats.snareContacts = snare.contacts;
        stats.maxSnarePenetration_m = std::max(stats.maxSnarePenetration_m, snare.maxPenetration_m);
    }
    if (iterations > 0)
    {
        stats.lastIterations = iterations;
        stats.maxIterations = std::max(stats.maxIterations, iterations);
    }
    if (fallback)
        ++stats.fallbacks;
}

template <class Lap>
[[gnu::noinline]] void Drum::stepCouplingsInAir(Lap& lap)
{
    // 1. The free updates: the air (eq. 25) and the components, the heads without pressure
    //    (the embeddings carry it, eq. 7).
    boxAir.computeFree();
    lap(StepPhase::airBegin);
    batterHead.computeFree();
    lap(StepPhase::batterFree);
    carryHead.computeFree();
    lap(StepPhase::carryFree);
    contacts.each([&](auto& contact) { contact.computeFree(lap); });

    // 2. Each head with its air (eq. 7-8) and its contacts, solved jointly (DrumAir.h): the
    //    contacts on that head tried again from their saved free updates until the air agrees.
    ContactSolves solves;
    auto jointly = [&](auto head) {
        auto onHead = [&](auto&& f) {
            contacts.each([&](auto& contact) {
                if constexpr (std::decay_t<decltype(contact)>::head == std::decay_t<decltype(head)>::value)
                    f(contact);
            });
        };
        onHead([](auto& contact) { contact.saveTrial(); });
        auto trial = [&] { onHead([&](auto& contact) { contact.solve(solves); }); };
        auto restore = [&] { onHead([](auto& contact) { contact.restoreTrial(); }); };
        if constexpr (std::decay_t<decltype(head)>::value == 0)
            return boxAir.solveBatter(trial, restore);
        else
            return boxAir.solveCarry(trial, restore);
    };
    const auto onBatter = jointly(std::integral_constant<int, 0> {});
    lap(StepPhase::batterJoint);
    const JointSolveResult onCarry = jointly(std::integral_constant<int, 1> {});
    noteSolves(solves);
    stats.maxAirTrials = std::max({ stats.maxAirTrials, onBatter.trials, onCarry.trials });
    stats.airCapped += (onBatter.capped ? 1 : 0) + (onCarry.capped ? 1 : 0);
    stats.airTrials += onBatter.trials + onCarry.trials;
    stats.maxAirMismatch = std::max({ stats.maxAirMismatch, onBatter.mismatch, onCarry.mismatch });
    lap(StepPhase::carryJoint);
    boxAir.joinAir(); // the rest of the air's update (step 1) ran meanwhile on the air's threads
    lap(StepPhase::airJoin);
    boxAir.listen();
    lap(StepPhase::signals);
}

double Drum::step()
{
    ++samplesRendered;
    const int up = toHost.factor(), down = toHost.down();
    if (up == 1)
        return simulate();
    if (hostPhase < down) // the phase passed a multiple of L: a simulated sample is due
    {
        simulate();
        toHost.push({ signals.mix, signals.top_Pa, signals.bottom_Pa, signals.room_Pa });
    }
    lastPhase = hostPhase;
    hostPhase = hostPhase + down >= up ? hostPhase + down - up : hostPhase + down;
    return toHost.value(0, lastPhase);
}

double Drum::simulate()
{
    if (profiling)
    {
        PhaseClock<true> lap(stepProfile);
        return stepWith(lap);
    }
    PhaseClock<false> lap(stepProfile);
    return stepWith(lap);
}

template <class Lap>
double Drum::stepWith(Lap& lap)
{
    if (boxAir.active())
        stepCouplingsInAir(lap);
    else
        stepCouplings(lap);
    retrieveRisingMallets();
    lap(StepPhase::malletsFree);

    cavityCoupling.step(); // dV^{n+1}
    CellSums taken;        // the heads' cell sums the attached air takes this step
    attachedAir.each([&](auto& air) {
        if (air.active())
        {
            air.afterHeads(taken); // q^{n+1}
            taken.add(air);
        }
    });
    lap(boxAir.active() ? StepPhase::signals : StepPhase::cavity); // the air box path counts it with the signals

    // 3. Energy at n + 1/2 and the microphones, then every time level moves on.
    if (trackEnergy)
    {
        updateEnergy();
        lap(StepPhase::energy);
    }

    // the cells' sums of this step, where a coupling has taken them already
    pressureMics.listen(batterHead, carryHead, { taken.at(0, pressureMics.cellSide(0)), taken.at(1, pressureMics.cellSide(1)) });
    const bool boxMics = boxAir.active() && cfg.airBox.numMics == 0; // the box's microphones are the drum's
    signals.top_Pa = boxMics ? boxAir.micPressure(0) : pressureMics.pressure(PressureMicrophones::top);
    signals.bottom_Pa = boxMics ? boxAir.micPressure(1) : pressureMics.pressure(PressureMicrophones::bottom);
    signals.room_Pa = boxMics ? boxAir.micPressure(2) : pressureMics.pressure(PressureMicrophones::room);
    if (room.active())
    {
        // The room hears the drum as the room microphone does, brought to 1 m (the free field
        // falls as 1 / r), and its diffuse field joins every microphone (DiffuseRoom.h).
        const AirPoint& r = cfg.mics.room;
        const auto diffuse = room.listen(signals.room_Pa * std::sqrt(r.x_m * r.x_m + r.y_m * r.y_m + r.z_m * r.z_m));
        signals.top_Pa += diffuse[0];
        signals.bottom_Pa += diffuse[1];
        signals.room_Pa += diffuse[2];
    }
    const auto& m = cfg.mics;
    signals.mix = cfg.outputGain * (m.mixTop * m.topGain * signals.top_Pa + m.mixBottom * m.bottomGain * signals.bottom_Pa +
                                    m.mixRoom * m.roomGain * signals.room_Pa);
    lap(StepPhase::signals);

    batterHead.advance();
    carryHead.advance();
    contacts.each([](auto& contact) { contact.advance(); });
    cavityAir.advance();
    attachedAir.each([](auto& air) {
        if (air.active())
            air.advance();
    });
    if (boxAir.active())
        boxAir.advance();
    lap(StepPhase::advance);
    return signals.mix;
}

double Drum::output(Mic mic) const
{
    const auto& m = cfg.mics;
    const bool interpolated = toHost.factor() > 1;
    auto at = [&](int channel, double simulated) { return interpolated ? toHost.value(channel, lastPhase) : simulated; };
    switch (mic)
    {
        case Mic::top: return cfg.outputGain * m.topGain * at(1, signals.top_Pa);
        case Mic::bottom: return cfg.outputGain * m.bottomGain * at(2, signals.bottom_Pa);
        case Mic::room: return cfg.outputGain * m.roomGain * at(3, signals.room_Pa);
        case Mic::mix: break;
    }
    return at(0, signals.mix);
}

void Drum::retrieveRisingMallets()
{
    // A mallet that has left the head and rises past kRetrieveHeight is taken back by the
    // player: it leaves the model with its energy (counted in the ledger), so a free flight
    // never grows z to where round-off would spoil the energy or the solve.
    for (auto& m : mallets)
        if (m.inPlay() && m.etaNext < -kRetrieveHeight_m && m.etaNow < 0.0 && m.zNext > m.zNow)
        {
            const double e = m.energy() + MalletContact::potentialEnergy(m);
            ledger.injected_J -= e;
            m.park();
        }
}

void Drum::updateEnergy() { record(ledger, energyTerms()); }

void Drum::process(float* out, int n)
{
    for (int i = 0; i < n; ++i)
        out[i] = (float) step();
}

void Drum::reset()
{
    batterHead.clear();
    carryHead.clear();
    contacts.each([](auto& contact) { contact.clear(); });
    cavityAir.clear();
    attachedAir.each([](auto& air) { air.clear(); });
    boxAir.clear();
    ledger.clearValues();
    signals = {};
    pressureMics.clear();
    room.clear();
    toHost.clear();
    hostPhase = lastPhase = 0;
    samplesRendered = 0;
}

} // namespace snaresim
