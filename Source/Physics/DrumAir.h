#pragma once
// The drum inside the air box (AirModel::airbox; docs/MODEL.md, "The drum in the air box"):
// the 3D air (eq. 5, 25, 41, 51) with the rigid shell (eq. 6), the batter embedded at z = +H/2
// and the carry head at z = -H/2 (eq. 7-8), each closing one end of the shell: the air inside
// the shell lies between them, the outside air all around. A component for the ledger: the
// air's energy (eq. 36) and losses; the embeddings store none.
//
// The joint solve. A head's update with its air is A w^{n+1} = r with A = 1 + gamma J^T J
// (HeadEmbedding.h), so a contact force distribution g moves the head by A^{-1} g, not by g.
// J links each head node to one group of air nodes, so A^{-1} is 1 - gain_g 1 1^T on each group
// of head nodes: the embedding gives the head the diagonal of A^{-1} as its response to forces
// (Membrane::forceGainAt), and the contacts (MalletContact, SnareContact) solve with it. Where a
// group holds one head node (the head coarser than the air: the carry head at the default
// Quality) that response is exact and one trial is the joint solution. Where a group holds
// several (the batter), a force at one node also pulls the group's other nodes by gain_g times
// its vacuum response (gain_g about 0.003 for the default batter), and around the contacts runs
// an iteration on that pull, node by node: the contacts see the head r - x and add their
// response; the embedding makes the head exactly A^{-1} (r + delta) and finds the pull x each
// node should have seen; the next trial sees that, extrapolated through the last two trials:
// for the snares (each acts at one node) with each node's response to its own pull taken
// linear, for the mallets (one force over a patch) along each node's secant. A group the
// contacts moved in the last step starts from the pull it ended that step with. The iteration
// stops when no node's pull changes by more than round-off; where it stops contracting (a
// contact switching on and off between trials) the pull the contacts see next is damped. The
// last trial's forces are what the head, its air and the contacts all see: at the fixed point
// the energy identity holds; past the cap (counted) the mismatch is the last change of the pull.

#include "AirBox.h"
#include "DrumAirSpec.h"
#include "HeadEmbedding.h"
#include "Membrane.h"

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <vector>

namespace snaresim
{

struct JointSolveResult
{
    int trials = 0;        // contact solves this step (1 when the contacts exert no force)
    bool capped = false;   // stopped at maxTrials before the pull settled
    double mismatch = 0.0; // the last trial's mismatch (HeadEmbedding::correct) / max |w| over the head
};

class DrumAir
{
public:
    static constexpr int maxTrials = 100;
    static constexpr double tolerance = 1.0e-15;      // change of the pull / max |w| over the head
    static constexpr double stallTolerance = 1.0e-12; // stop when the change stops falling below this

    DrumAir() = default; // no air box: inactive, energy 0
    DrumAir(const DrumAir&) = delete;
    DrumAir& operator=(const DrumAir&) = delete;

    // The air box of this spec around batter and carry (both must outlive it; the heads close the
    // shell's ends at +-shellDepth_m / 2), its update on this many threads, steps of
    // timeStep_s. Throws std::invalid_argument. No microphones until placeMics.
    void build(const AirBoxSpec& spec, int threads, double shellDepth_m, double timeStep_s, Membrane& batter, Membrane& carry);
    bool active() const { return box != nullptr; }

    const AirBox& air() const { return *box; }
    const HeadEmbedding& batterEmbedding() const { return *top; }
    const HeadEmbedding& carryEmbedding() const { return *bottom; }

    // The air's own update (eq. 25), before the heads' free updates are coupled. The two
    // layers around each head (the embeddings read and write only those) are final when it
    // returns; the air box's threads compute the others meanwhile, until joinAir().
    void computeFree()
    {
        const int d = top->layer(), e = bottom->layer();
        const int layers[4] = { e, e + 1, d, d + 1 };
        box->beginNext(layers);
    }
    // The rest of the air's update (after both heads are solved, before anything else reads it).
    void joinAir() { box->finishNext(); }

    // One head with its air and its contacts (after every free update): trial() solves the
    // contacts from the free state and writes the head's w^{n+1}; restore() puts the contacts'
    // own state (mallets' z, wires' u, ...) back to the free state for another trial.
    template <class Trial, class Restore>
    JointSolveResult solveBatter(Trial&& trial, Restore&& restore)
    {
        return solve(*top, false, trial, restore);
    }
    template <class Trial, class Restore>
    JointSolveResult solveCarry(Trial&& trial, Restore&& restore)
    {
        return solve(*bottom, true, trial, restore);
    }

    // The pressure microphones rho_a dt+ Psi at n+1/2 (after both heads are solved).
    void listen();
    int numMics() const { return micCount; }
    const AirPoint& micPoint(int i) const { return points[(size_t) i]; }
    double micPressure(int i) const { return pressures[(size_t) i]; }
    // The pressure microphones: the first count of these points. Allocates nothing.
    void placeMics(const std::array<AirPoint, DrumAirSpec::maxMics>& points, int count);

    // Call after a head's coefficients change (its sigma0 enters the solve). Allocates nothing.
    void refresh();

    double energy() const { return box ? box->energy() : 0.0; }
    double stepLoss() const { return box ? box->stepLoss() : 0.0; }
    void advance() { box->advance(); }
    void clear();

private:
    template <class Trial, class Restore>
    JointSolveResult solve(HeadEmbedding& e, bool pointwise, Trial& trial, Restore& restore)
    {
        JointSolveResult result;
        e.solveFree(true);
        double last = std::numeric_limits<double>::infinity(), omega = 1.0;
        for (;;)
        {
            ++result.trials;
            trial();
            const double change = e.correct(), scale = e.scale();
            result.mismatch = scale > 0.0 ? change / scale : 0.0;
            if (change <= tolerance * scale || (change >= last && change <= stallTolerance * scale))
                break;
            if (result.trials >= maxTrials)
            {
                result.capped = true;
                break;
            }
            if (change >= last) // not contracting (a contact switching on and off): damp
                omega = std::max(0.5 * omega, 1.0 / 64.0);
            last = change;
            e.retry(omega, pointwise);
            restore();
        }
        e.finish(); // eq. (8) with the final w^{n+1}
        return result;
    }

    std::unique_ptr<AirBox> box;
    std::unique_ptr<HeadEmbedding> top, bottom;
    std::array<AirPoint, DrumAirSpec::maxMics> points {};
    std::array<double, DrumAirSpec::maxMics> pressures {};
    int micCount = 0;
};

} // namespace snaresim
