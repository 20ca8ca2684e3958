#pragma once
// A head embedded in the air box (eq. 7-8): the head lies in the horizontal plane between
// air layers d and u = d + 1, and the vertical links between them over the head are cut.
// Instead, the head's velocity is the air's normal velocity on both sides (eq. 8),
//   dtt Psi_u = ... + (c^2 / h_a) J dt. w,    dtt Psi_d = ... - (c^2 / h_a) J dt. w,
// and the pressure jump drives the head (eq. 7, F+ + F- = -rho_a dt (Psi_u - Psi_d)),
//   rho dtt w = ... - rho_a I dt. (Psi_u - Psi_d),   I = (h_a^2 / h_m^2) J^T,
// J the bilinear interpolation from the head's grid to the air layer. The power the head
// gives the air, rho_a h_a^2 (J dt. w)^T dt. (Psi_u - Psi_d), is exactly what it loses, so
// the coupling neither makes nor destroys energy.
//
// Both sides use dt. (centred), so w^{n+1} and Psi^{n+1} over the head are found together:
// (1 + gamma J^T J) w^{n+1} = r, solved exactly with Woodbury's identity through the
// air-side matrix 1 + gamma J J^T, factored once (sparse LDL^T; diagonal when h_a > h_m).

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <vector>

namespace snaresim
{

class AirBox;
class Membrane;

class HeadEmbedding
{
public:
    // The head's centre at (cx, cy) and its plane the air grid's plane nearest z.
    // Throws std::invalid_argument when the head does not fit inside the box with a cell to spare.
    HeadEmbedding(AirBox& air, Membrane& head, double z_m, double cx_m = 0.0, double cy_m = 0.0);

    // After air.computeNext() and head.computeFree() (and before any other force on the head):
    // adds the coupling to both next levels. The same as solveFree() then finish().
    void step();

    // The step in parts, for a head that another coupling (contacts) also moves this step.
    // The coupling's forces act through the head's vacuum gain; A w = r + delta with
    // A = 1 + gamma J^T J, so the air's share is found again from what the coupling added:
    //   solveFree(): w^{n+1} = A^{-1} r over the head (the air's next level untouched);
    //   correct():   after the coupling changed w^{n+1} by delta (its vacuum response, on top of
    //                the last retry()/solveFree() value), s = (1 + gamma J J^T)^{-1} J (r + delta)
    //                and w^{n+1} = r + delta - gamma J^T s, exactly A^{-1} (r + delta); returns
    //                the largest difference between that pull gamma J^T s and the one the trial
    //                saw (m): the contacts' mismatch; 0 when the first trial exerts no force;
    //   retry(omega): w^{n+1} = r - P, the head as the coupling should see it before its
    //                forces, for another trial, P = the last pull gamma J^T s moved by omega
    //                (0 < omega <= 1) of the way from the one before (the caller restores the
    //                nodes outside J's support);
    //   finish():    eq. (8) with the final w^{n+1}: adds the head's velocity to the air.
    void solveFree();
    double correct();
    void retry(double omega = 1.0);
    void finish();
    // Largest |w^{n+1}| over J's support after solveFree(): the scale of correct()'s change.
    double scale() const { return wScale; }

    // Call after the head's coefficients change (its sigma0 enters the solve).
    void refresh();

    int layer() const { return d; }
    double planeZ() const;
    int airNodes() const { return (int) below.size(); }  // air nodes over the head, per layer
    int headNodes() const { return (int) support.size(); } // head nodes J reaches

private:
    AirBox& air;
    Membrane& head;
    int d = 0;
    long up = 0;                 // index offset from layer d to layer d + 1
    std::vector<long> below;     // air nodes of layer d under the head (rows of J)
    std::vector<int> support;    // head nodes J reaches (columns of J)
    Eigen::SparseMatrix<double, Eigen::RowMajor> J;
    Eigen::SparseMatrix<double, Eigen::RowMajor> Jt;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
    double alpha = 0, beta = 0, ratio = 0, gamma = 0;
    double wScale = 0;
    bool fresh = false; // no retry() since solveFree()
    Eigen::VectorXd wFree, wPrev, r, y, jr, dv; // work vectors
    Eigen::VectorXd s, sNew, pull, base, w, jts; // air-side vector, gamma J^T s, r - gamma J^T s, w^{n+1}
    Eigen::VectorXd seen;                        // the pull the last trial saw
};

} // namespace snaresim
