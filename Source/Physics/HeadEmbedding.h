#pragma once
// A head embedded in the air box (eq. 7-8): the head lies in the horizontal plane between
// air layers d and u = d + 1, and the vertical links between them over the head are cut.
// Instead, the head's velocity is the air's normal velocity on both sides (eq. 8),
//   dtt Psi_u = ... + (c^2 / h_a) J dt. w,    dtt Psi_d = ... - (c^2 / h_a) J dt. w,
// and the pressure jump drives the head (eq. 7, F+ + F- = -rho_a dt (Psi_u - Psi_d)),
//   rho dtt w = ... - rho_a I dt. (Psi_u - Psi_d),   I = (h_a^2 / h_m^2) J^T.
// The power the head gives the air, rho_a h_a^2 (J dt. w)^T dt. (Psi_u - Psi_d), is exactly
// what it loses, so the coupling neither makes nor destroys energy, whatever J is.
//
// J is piecewise constant and conserves volume: each point of the finer grid is linked to the
// nearest point of the coarser one, and the air nodes linked to head nodes pass on exactly the
// volume those sweep (sum_a h_a^2 (J w)_a = h_m^2 sum_j w_j).
//   - Air coarser than the head (h_a >= h_m): each interior head node belongs to the air node
//     over the head nearest it (a node whose nearest air node lies beyond the cut disc, at the
//     rim, to the nearest one within it), and (J w)_a = (h_m^2 / h_a^2) times the sum of its
//     nodes' w. An air node with no head node stays rigid.
//   - Head coarser (h_m > h_a): each air node over the head moves with its nearest head node j,
//     (J w)_a = (h_m^2 / (m_j h_a^2)) w_j, m_j the air nodes of node j; an air node whose nearest
//     head node is on the fixed rim stays rigid.
// I = (h_a^2 / h_m^2) J^T then gives each head node the mean pressure jump over its air node(s).
// The head nodes and the air nodes fall into disjoint groups (one air node with its head nodes,
// or one head node with its air nodes), J is constant on each group, and J^T J = kappa_g 1 1^T
// on group g (kappa_g = its air nodes times J's value squared). Both sides use dt. (centred), so
// w^{n+1} and Psi^{n+1} over the head are found together from (1 + gamma J^T J) w^{n+1} = r,
// solved exactly group by group (Sherman-Morrison): every node of group g loses the same pull
//   P_g = gain_g S_g,   gain_g = gamma kappa_g / (1 + gamma kappa_g n_g),   S_g = the sum of r over its n_g nodes.
// No factorisation, nothing to refactor: a step is one pass over the head's nodes and the air
// nodes over it.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace snaresim
{

class AirBox;
class Membrane;

class HeadEmbedding
{
public:
    // The head's centre at (cx, cy) and its plane the air grid's plane nearest z. Sets the
    // head's response to forces (Membrane::setResponse) to the diagonal of A^{-1} (below).
    // Throws std::invalid_argument when the head does not fit inside the box with a cell to spare.
    HeadEmbedding(AirBox& air, Membrane& head, double z_m, double cx_m = 0.0, double cy_m = 0.0);
    ~HeadEmbedding();
    HeadEmbedding(const HeadEmbedding&) = delete;
    HeadEmbedding& operator=(const HeadEmbedding&) = delete;

    // After air.computeNext() and head.computeFree() (and before any other force on the head):
    // adds the coupling to both next levels. The same as solveFree() then finish().
    void step();

    // The step in parts, for a head that another coupling (contacts) also moves this step.
    // A w = r + delta with A = 1 + gamma J^T J and delta the coupling's vacuum response; the
    // coupling moves each node j by response_j delta_j, response_j = (A^{-1})_jj = 1 - gain_g
    // (Membrane::forceGainAt), so the node's own share of the air's pull is in what it sees.
    // What is left, the pull of its group's other nodes, is what the trials iterate on (when a
    // group holds one head node, as where the head is coarser than the air, nothing is left:
    // one trial is exact):
    //   solveFree(warm): w^{n+1} = A^{-1} r over the head (the air's next level untouched);
    //                warm: where the coupling moved a group of several nodes in the last step,
    //                those nodes start from the pull they ended it with;
    //   correct():   after the coupling changed w^{n+1}, the exact w^{n+1} = A^{-1} (r + delta)
    //                on the groups it moved; returns the largest difference between the pull a
    //                node saw and its exact one (m): the coupling's mismatch; 0 when the first
    //                trial moves no head node;
    //   retry(omega, pointwise): the whole head back as the trial found it, each node with its
    //                next pull for another trial: omega < 1, the pull seen moved by omega of the
    //                way to the exact one; omega = 1 and pointwise (a coupling that acts node by
    //                node, its response at a node depending on that node only: the snares), the
    //                group's pulls solved with that response taken linear (its slope the secant
    //                through the last two trials, or the node's last one); omega = 1 and not
    //                pointwise (forces spread over several nodes: a mallet), each node's exact
    //                pull against the one seen taken linear through the last two trials;
    //   finish():    eq. (8) with the final w^{n+1}: adds the head's velocity to the air.
    void solveFree(bool warm = false);
    double correct();
    void retry(double omega = 1.0, bool pointwise = true);
    void finish();
    // Largest |w^{n+1}| over the head as the last trial left it: the scale of correct()'s change.
    double scale() const { return wScale; }
    // Groups the coupling has moved this step (after correct()).
    int movedGroups() const { return (int) active.size(); }

    // Call after the head's coefficients change (its sigma0 enters the solve). Allocates nothing.
    void refresh();
    // Forget the groups the coupling moved (this step's and the last one's).
    void clear();

    int layer() const { return d; }
    double planeZ() const;
    int airNodes() const { return (int) below.size(); }  // air nodes over the head, per layer
    int headNodes() const { return (int) nodes.size(); } // head nodes J reaches
    int groups() const { return (int) count.size(); }
    bool airCoarser() const { return coarserAir; }
    // h_a^2 sum_a (J 1)_a / (h_m^2 headNodes()): the volume the air sees swept when every head
    // node J reaches moves by one, over the volume the head sweeps (1: J conserves volume).
    double volumeRatio() const;

private:
    void activate(int group);
    void forget(); // no group moved yet this step

    AirBox& air;
    Membrane& head;
    int d = 0;
    long up = 0;             // index offset from layer d to layer d + 1
    std::vector<long> below; // air nodes of layer d under the head (the cut links)
    bool coarserAir = true;
    // Groups, each a run of head nodes and a run of air nodes (layer d) with J = value there.
    std::vector<int> nodes;     // head nodes, group by group
    std::vector<long> cells;    // air nodes, group by group
    std::vector<int> nodeBegin; // group g's head nodes: nodes[nodeBegin[g] .. nodeBegin[g + 1])
    std::vector<int> cellBegin; // group g's air nodes: cells[cellBegin[g] .. cellBegin[g + 1])
    std::vector<int> groupOf;   // per head node (padded grid): its group, or -1
    std::vector<int> cellGroup; // per air node (in cells' order): its group
    struct Run                  // groups first .. last - 1, each of `nodes` head and `cells` air nodes
    {
        std::size_t first, last;
        int nodes, cells;
    };
    std::vector<Run> runs;
    std::vector<double> count;       // n_g
    std::vector<double> value;       // J's value on the group: h_m^2 / (its air nodes h_a^2)
    std::vector<double> gain;        // P_g = gain_g S_g: gamma kappa_g / (1 + gamma kappa_g n_g)
    std::vector<double> invResponse; // 1 / (1 - gain_g)
    std::vector<double> response;    // per head node (padded grid): 1 - gain of its group, or 1
    double alpha = 0, beta = 0, ratio = 0, gamma = 0;
    double wScale = 0;
    bool fresh = false; // no retry() since solveFree()

    // per group: the sum of w^{n-1} and of r, the exact pull for r, and what eq. (8) adds to
    // Psi_u (and takes from Psi_d) at each of its air nodes
    std::vector<double> sumPrev, sumR, pullFree, airStep;
    // per head node (in nodes' order): r, the pull the last trial saw and its exact one, the
    // coupling's vacuum response delta there, the same for the trial before, the slope of delta
    // against the pull seen (kept from step to step), and the pull beyond the free one the node
    // ended the last step with (the warm start, for the groups in warmGroups)
    std::vector<double> rNode, seenNode, exactNode, deltaNode, seenOld, exactOld, deltaOld, sigma, warmNode;
    std::vector<double> start;   // w^{n+1} (the whole padded grid) as the trial started
    double startSum = 0.0;       // its sum, for Membrane::restoreNext
    std::vector<int> active;     // the groups the coupling moved this step
    std::vector<int> warmGroups; // the groups of several nodes it moved in the last step
    std::vector<std::uint8_t> isActive;
};

} // namespace snaresim
