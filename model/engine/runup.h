// The run-up engine: nonlinear time integration of the rotor with its force elements under a prescribed speed.
//
// State y = [q (n), v = q' (n), z (internal states of all force elements, m), E_in, E_diss], with
//   M v' = f_g + f_u(t) - (D + Omega G) v - (K + Omega' G) q + sum_e f_e(q, v, z, t)
//   z'   = g(q, v, z, t)
// q are the rotor coordinates: the physical FE DOFs, or (default) a Craig-Bampton reduction of them,
//   u = T q,  q = [u_B; eta],  T = [I 0; Psi Phi]
// where u_B are the translations force elements act on and the disks' translations (kept exactly), Psi the static constraint
// modes and Phi the fixed-interface normal modes below a cutoff frequency (Craig & Bampton 1968, AIAA J. 6(7)).
// The Timoshenko mesh has element-level modes near 1e7 rad/s that force any BDF method above order 2 into
// tiny steps; the reduction removes them while keeping the bearing DOFs exact (see bench/README.md).
// f_u are the unbalance forces of the spinning disks (including the angular-acceleration term), Omega' G q the
// gyroscopic term of the spin acceleration (d/dt of Ip Omega (theta_y, -theta_x)), and E_in, E_diss accumulate the
// work of the unbalance/spin-acceleration terms and the dissipated energy for the energy balance.
//
// A RunupModel is immutable and shared; each simulation owns a RunupWorkspace (model/workspace split, so that
// parallel studies can run many simulations of one model). Rhs() allocates nothing.
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "model/elements/force_element.h"
#include "model/spec/model_spec.h"
#include "model/rotor/rotor.h"
#include "model/engine/speed_profile.h"

namespace turbodyn {

/// One output channel of a run.
struct ProbeChannel {
  enum class Kind { Speed, Angle, RotorDof, Element };
  ProbeChannel() = default;
  ProbeChannel(std::string name_, std::string unit_, std::string description_, Kind kind_, int index_,
               int element_probe_, double limit_ = std::numeric_limits<double>::infinity(),
               std::string limit_note_ = {}, bool limit_below_ = false)
      : name(std::move(name_)), unit(std::move(unit_)), description(std::move(description_)), kind(kind_),
        index(index_), element_probe(element_probe_), limit(limit_), limit_note(std::move(limit_note_)),
        limit_below(limit_below_) {}

  std::string name;         ///< e.g. "disk.compressor.x"
  std::string unit;         ///< e.g. "m"
  std::string description;
  Kind kind = Kind::RotorDof;
  int index = 0;            ///< rotor DOF (RotorDof) or element index (Element)
  int element_probe = 0;    ///< index among the element's probes
  /// The element probe's limit and what passing it means (ProbeInfo::limit; infinite: none); `limit_below`: the
  /// limit is a smallest value (ProbeInfo::limit_below).
  double limit = std::numeric_limits<double>::infinity();
  std::string limit_note;
  bool limit_below = false;
};

struct RunupWorkspace;
/// Owns a workspace (its layout is private to the engine).
struct RunupWorkspaceDeleter {
  void operator()(RunupWorkspace* ws) const;
};
using RunupWorkspacePtr = std::unique_ptr<RunupWorkspace, RunupWorkspaceDeleter>;

class RunupModel {
 public:
  /// `reduction_cutoff` (Hz): keep fixed-interface modes below it; 0 = no reduction (physical DOFs).
  RunupModel(const MachineSpec& spec, Rotor rotor, std::vector<std::unique_ptr<ForceElement>> elements,
             double reduction_cutoff);
  ~RunupModel();
  RunupModel(const RunupModel&) = delete;
  RunupModel& operator=(const RunupModel&) = delete;

  const MachineSpec& spec() const { return spec_; }
  const Rotor& rotor() const { return rotor_; }
  const SpeedFunction& speed() const { return speed_; }
  const std::vector<std::unique_ptr<ForceElement>>& elements() const { return elements_; }
  int n_dof() const { return n_coordinates_; }    ///< rotor coordinates (reduced or physical)
  int n_physical_dof() const { return rotor_.n_dof; }
  const Eigen::MatrixXd& mass() const { return M_; }
  /// u = T q: physical displacements from the rotor coordinates (n_physical_dof x n_dof).
  const Eigen::MatrixXd& reduction_basis() const { return T_; }
  /// Lowest fixed-interface mode dropped by the reduction (Hz), or 0 when nothing was dropped.
  double reduction_cutoff() const { return cutoff_; }
  int n_element_states() const { return n_element_states_; }
  int n_states() const { return 2 * n_coordinates_ + n_element_states_ + 2; }
  int state_offset(int element) const { return state_offsets_[element]; }  ///< into y
  const std::vector<ProbeChannel>& channels() const { return channels_; }

  /// threads > 1: the force elements of one right-hand side and Jacobian are evaluated side by side on up to
  /// that many threads (one per element at most); the results are the same as with one.
  RunupWorkspacePtr make_workspace(int threads = 1) const;
  SpinState spin(double t) const;

  /// y' = F(t, y). Allocation-free.
  void Rhs(double t, const double* y, double* ydot, RunupWorkspace& ws) const;
  /// Values of all channels at (t, y), in channels() order.
  void Probes(double t, const double* y, RunupWorkspace& ws, double* out) const;
  /// Fills the Jacobian blocks of ws (F_q, F_v, F_z, G_q, G_v, G_z) at (t, y): exact for the rotor, analytic or
  /// forward differences for the elements.
  void Jacobian(double t, const double* y, RunupWorkspace& ws) const;
  /// Moves the last Jacobian's rotor terms that depend on the spin (-Omega G in dF/dv, -Omega' G in dF/dq) to the
  /// spin at t, exactly; the elements' blocks are kept as they were (the integrator's cheap refresh when only the
  /// speed has moved).
  void RespinJacobian(double t, RunupWorkspace& ws) const;
  /// Initial state: element initial states, then (static_equilibrium) the static equilibrium under gravity at t;
  /// throws std::runtime_error if Newton's method fails.
  void InitialState(double t, bool static_equilibrium, double* y, RunupWorkspace& ws) const;
  /// Kinetic + potential energy (gravity included) at (t, y), J.
  double MechanicalEnergy(double t, const double* y) const;
  /// Factors the Newton matrix I - gamma dF/dy of the BDF corrector at the last Jacobian(). With dq = r_q + gamma dv
  /// it reduces to
  ///   [ M - g Fv - g^2 Fq      -g Fz   ] [dv]   [ M r_v + g Fq r_q ]
  ///   [ -g (Gv + g Gq)      I - g Gz   ] [dz] = [ r_z + g Gq r_q   ]
  /// whose lower-right block is block-diagonal (each element's states depend on its own states only). Each block is
  /// factored on its own and eliminated, leaving an n x n Schur complement on the rotor coordinates: for two
  /// 82-state ball bearings about 10x fewer operations than factoring the (n + m) matrix whole. Within an element,
  /// independent state blocks (ForceElement::independent_state_blocks(): a ball bearing's balls) are eliminated one
  /// by one onto the element's border (BlockArrowLU). Returns false if a factor is singular. Allocation-free.
  bool FactorNewton(double gamma, RunupWorkspace& ws) const;
  /// Solves (I - gamma dF/dy) x = b with the factors of FactorNewton() (b, x: n_states() values; the two
  /// energy-accounting states are passed through). Allocation-free.
  void SolveNewton(double gamma, const double* b, double* x, RunupWorkspace& ws) const;
  /// Absolute tolerance of each state (n_states() values) for a displacement tolerance atol (m). scaled: every
  /// state's tolerance is atol times its typical magnitude over 1 um: rotor displacements 1 um, rotor velocities
  /// 1 mm/s, element states ForceElement::tolerance_scale() (by default the magnitudes the finite-difference
  /// Jacobian uses, ForceElement::state_scale(); larger for the velocities of fast parts such as balls),
  /// energy accounts 1 J per um, i.e. each state is resolved to the same fraction of its typical size. Otherwise
  /// atol for every state.
  Eigen::VectorXd AbsoluteTolerances(double atol, bool scaled) const;
  /// Whether an element's absolute tolerances depend on its state (ForceElement::has_state_dependent_tolerances);
  /// then the integrator takes its error weights from AbsoluteToleranceFactors at every step.
  bool HasStateDependentTolerances() const;
  /// Factors on AbsoluteTolerances() at the state y: 1, and the elements' own for their states.
  void AbsoluteToleranceFactors(const double* y, double* f) const;
  /// The Jacobian dF/dy (n_states x n_states) assembled from the blocks of Jacobian(); the rows of the two
  /// energy-accounting states are left zero. For tests and diagnostics.
  Eigen::MatrixXd JacobianMatrix(double t, const double* y, RunupWorkspace& ws) const;

 private:
  void Gather(const ForceElement& e, const double* q, const double* v, RunupWorkspace& ws, int k) const;

  MachineSpec spec_;
  Rotor rotor_;
  SpeedFunction speed_;
  std::vector<std::unique_ptr<ForceElement>> elements_;
  std::vector<int> state_offsets_;
  int n_element_states_ = 0;
  int n_coordinates_ = 0;
  double cutoff_ = 0.0;
  Eigen::MatrixXd T_;                 // u = T q
  Eigen::MatrixXd M_, K_, D_, G_;     // in rotor coordinates
  Eigen::VectorXd gravity_;           // T' f_g
  std::vector<Eigen::MatrixXd> element_rows_;  // per element: rows of T for its DOFs (u_e = R q)
  struct DiskRows {
    Eigen::RowVectorXd x, y;          // rows of T for the disk's x and y
  };
  std::vector<DiskRows> disk_rows_;
  Eigen::MatrixXd M_inverse_;
  std::vector<ProbeChannel> channels_;
};

/// Builds the run-up model of a machine: rotor (reduced as spec.solver says), one force element per bearing.
std::unique_ptr<RunupModel> make_runup_model(const MachineSpec& spec);

}  // namespace turbodyn
