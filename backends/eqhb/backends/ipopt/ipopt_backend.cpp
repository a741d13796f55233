#include "eqhb/backends/ipopt/ipopt_backend.h"

#include <IpIpoptApplication.hpp>
#include <algorithm>
#include <IpTNLP.hpp>

namespace eqhb {

namespace {

using Ipopt::Index;
using Ipopt::Number;

class SystemNlp : public Ipopt::TNLP {
 public:
  // sparse: Jacobian (and Gauss–Newton Hessian) in the system's sparse
  // pattern, never as dense n x n matrices.
  SystemNlp(MonitoredSystem& system, const SolverOptions& options, const Eigen::VectorXd& z0,
            bool least_squares, bool gauss_newton, bool sparse)
      : system_(system), options_(options), z0_(z0), least_squares_(least_squares),
        gauss_newton_(gauss_newton), sparse_(sparse), n_(system.size()), z_(n_), g_(n_) {
    if (!sparse_) {
      j_.resize(n_, n_);
      return;
    }
    sparse_j_ = system.jacobianPattern();
    if (least_squares_ && gauss_newton_) {
      // Pattern of JᵀJ (lower triangle) from the pattern with unit values:
      // no cancellation can hide an entry.
      SparseMatrix ones = sparse_j_;
      std::fill(ones.valuePtr(), ones.valuePtr() + ones.nonZeros(), 1.0);
      hessian_pattern_ = SparseMatrix(ones.transpose() * ones).triangularView<Eigen::Lower>();
      hessian_pattern_.makeCompressed();
    }
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = n_;
    m = least_squares_ ? 0 : n_;
    nnz_jac_g = least_squares_ ? 0 : sparse_ ? static_cast<Index>(sparse_j_.nonZeros()) : n_ * n_;
    nnz_h_lag = !(least_squares_ && gauss_newton_) ? 0
                : sparse_ ? static_cast<Index>(hessian_pattern_.nonZeros())
                          : n_ * (n_ + 1) / 2;
    index_style = C_STYLE;
    return true;
  }
  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    for (Index i = 0; i < n; ++i) {
      x_l[i] = -2e19;  // Ipopt's "no bound"
      x_u[i] = 2e19;
    }
    for (Index i = 0; i < m; ++i) g_l[i] = g_u[i] = 0.0;
    return true;
  }
  bool get_starting_point(Index n, bool, Number* x, bool, Number*, Number*, Index, bool,
                          Number*) override {
    for (Index i = 0; i < n; ++i) x[i] = z0_[i];
    return true;
  }
  bool eval_f(Index, const Number* x, bool new_x, Number& f) override {
    if (!least_squares_) {
      f = 0.0;
      return true;
    }
    if (!residualAt(x, new_x)) return false;
    f = 0.5 * g_.squaredNorm();
    return true;
  }
  bool eval_grad_f(Index n, const Number* x, bool new_x, Number* grad) override {
    Eigen::Map<Eigen::VectorXd> out(grad, n);
    if (!least_squares_) {
      out.setZero();
      return true;
    }
    if (!jacobianAt(x, new_x)) return false;
    if (sparse_) out.noalias() = sparse_j_.transpose() * g_;
    else out.noalias() = j_.transpose() * g_;
    return true;
  }
  bool eval_g(Index, const Number* x, bool new_x, Index m, Number* g) override {
    if (least_squares_) return true;  // no constraints
    if (!residualAt(x, new_x)) return false;
    Eigen::Map<Eigen::VectorXd>(g, m) = g_;
    return true;
  }
  bool eval_jac_g(Index, const Number* x, bool new_x, Index, Index, Index* rows, Index* cols,
                  Number* values) override {
    if (least_squares_) return true;  // no constraints
    if (sparse_) {  // the system's pattern, column by column
      if (values == nullptr) {
        listEntries(sparse_j_, rows, cols);
        return true;
      }
      if (!jacobianAt(x, new_x)) return false;
      std::copy(sparse_j_.valuePtr(), sparse_j_.valuePtr() + sparse_j_.nonZeros(), values);
      return true;
    }
    if (values == nullptr) {  // dense structure, row by row
      for (Index i = 0, k = 0; i < n_; ++i)
        for (Index c = 0; c < n_; ++c, ++k) {
          rows[k] = i;
          cols[k] = c;
        }
      return true;
    }
    if (!jacobianAt(x, new_x)) return false;
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(values, n_, n_) = j_;
    return true;
  }
  bool eval_h(Index, const Number* x, bool new_x, Number obj_factor, Index, const Number*, bool,
              Index, Index* rows, Index* cols, Number* values) override {
    // Only the least-squares form with Gauss–Newton gets here: obj_factor · JᵀJ.
    if (sparse_) {
      if (values == nullptr) {
        listEntries(hessian_pattern_, rows, cols);
        return true;
      }
      if (!jacobianAt(x, new_x)) return false;
      const SparseMatrix h = SparseMatrix(sparse_j_.transpose() * sparse_j_).triangularView<Eigen::Lower>();
      std::fill(values, values + hessian_pattern_.nonZeros(), 0.0);
      for (int c = 0; c < h.outerSize(); ++c)
        for (SparseMatrix::InnerIterator it(h, c); it; ++it) {
          const int* begin = hessian_pattern_.innerIndexPtr() + hessian_pattern_.outerIndexPtr()[c];
          const int* end = hessian_pattern_.innerIndexPtr() + hessian_pattern_.outerIndexPtr()[c + 1];
          const int* slot = std::lower_bound(begin, end, static_cast<int>(it.row()));
          if (slot != end && *slot == it.row())
            values[slot - hessian_pattern_.innerIndexPtr()] = obj_factor * it.value();
        }
      return true;
    }
    if (values == nullptr) {
      for (Index i = 0, k = 0; i < n_; ++i)
        for (Index c = 0; c <= i; ++c, ++k) {
          rows[k] = i;
          cols[k] = c;
        }
      return true;
    }
    if (!jacobianAt(x, new_x)) return false;
    const Eigen::MatrixXd h = obj_factor * (j_.transpose() * j_);
    for (Index i = 0, k = 0; i < n_; ++i)
      for (Index c = 0; c <= i; ++c, ++k) values[k] = h(i, c);
    return true;
  }
  void finalize_solution(Ipopt::SolverReturn status, Index n, const Number* x, const Number*,
                         const Number*, Index, const Number*, const Number*, Number,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    status_ = status;
    final_.assign(x, x + n);
  }
  bool intermediate_callback(Ipopt::AlgorithmMode, Index iter, Number, Number, Number, Number,
                             Number, Number, Number, Number, Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    iterations = iter;
    if (accepted.size() > 0) return false;
    if (system_.evaluationLimitReached()) {
      stop_reason = Termination::kEvaluationLimit;
      return false;
    }
    if (system_.timeLimitReached()) {
      stop_reason = Termination::kTimeLimit;
      return false;
    }
    return true;
  }

  int status() const { return static_cast<int>(status_); }
  const std::vector<double>& final() const { return final_; }
  Eigen::VectorXd accepted;  // a point with ‖g‖ <= tolerance, once seen
  Termination stop_reason = Termination::kConverged;
  int iterations = 0;

 private:
  // A new point forgets the residual and Jacobian of the last one.
  void moveTo(const Number* x, bool new_x) {
    if (!new_x && have_z_) return;
    z_ = Eigen::Map<const Eigen::VectorXd>(x, n_);
    have_z_ = true;
    have_g_ = have_j_ = false;
  }
  // The first point seen with ‖g‖ <= tolerance, kept.
  void keepIfAccepted() {
    if (accepted.size() == 0 && g_.norm() <= options_.residual_tolerance) accepted = z_;
  }
  bool residualAt(const Number* x, bool new_x) {
    moveTo(x, new_x);
    if (!have_g_) {
      if (!system_.residual(z_, g_)) return false;
      have_g_ = true;
      keepIfAccepted();
    }
    return true;
  }
  bool jacobianAt(const Number* x, bool new_x) {
    moveTo(x, new_x);
    if (!have_j_) {
      const bool ok = sparse_ ? system_.residualAndSparseJacobian(z_, g_, sparse_j_)
                              : system_.residualAndJacobian(z_, g_, j_);
      if (!ok) return false;
      have_g_ = have_j_ = true;
      keepIfAccepted();
    }
    return true;
  }

  // Ipopt's triplet structure of a compressed column-major matrix.
  static void listEntries(const SparseMatrix& m, Index* rows, Index* cols) {
    Index k = 0;
    for (int c = 0; c < m.outerSize(); ++c)
      for (SparseMatrix::InnerIterator it(m, c); it; ++it, ++k) {
        rows[k] = static_cast<Index>(it.row());
        cols[k] = c;
      }
  }

  MonitoredSystem& system_;
  const SolverOptions& options_;
  Eigen::VectorXd z0_;
  bool least_squares_, gauss_newton_, sparse_;
  Index n_;
  Eigen::VectorXd z_, g_;
  Eigen::MatrixXd j_;          // dense path
  SparseMatrix sparse_j_;      // sparse path: values in the system's pattern
  SparseMatrix hessian_pattern_;  // sparse Gauss–Newton: lower triangle of JᵀJ
  bool have_z_ = false, have_g_ = false, have_j_ = false;
  Ipopt::SolverReturn status_ = Ipopt::UNASSIGNED;
  std::vector<double> final_;
};

const char* solverReturnName(int status) {
  static const char* names[] = {"SUCCESS", "MAXITER_EXCEEDED", "CPUTIME_EXCEEDED", "STOP_AT_TINY_STEP",
                                "STOP_AT_ACCEPTABLE_POINT", "LOCAL_INFEASIBILITY", "USER_REQUESTED_STOP",
                                "FEASIBLE_POINT_FOUND", "DIVERGING_ITERATES", "RESTORATION_FAILURE",
                                "ERROR_IN_STEP_COMPUTATION", "INVALID_NUMBER_DETECTED",
                                "TOO_FEW_DEGREES_OF_FREEDOM", "INVALID_OPTION", "OUT_OF_MEMORY",
                                "INTERNAL_ERROR", "UNASSIGNED"};
  return status >= 0 && status <= 16 ? names[status] : "?";
}

}  // namespace

Termination ipoptTermination(int solver_return) {
  switch (static_cast<Ipopt::SolverReturn>(solver_return)) {
    case Ipopt::SUCCESS: return Termination::kConverged;
    case Ipopt::STOP_AT_ACCEPTABLE_POINT: return Termination::kConverged;
    case Ipopt::FEASIBLE_POINT_FOUND: return Termination::kConverged;
    case Ipopt::MAXITER_EXCEEDED: return Termination::kIterationLimit;
    case Ipopt::CPUTIME_EXCEEDED: return Termination::kTimeLimit;
    case Ipopt::STOP_AT_TINY_STEP: return Termination::kStepTolerance;
    case Ipopt::LOCAL_INFEASIBILITY: return Termination::kNotProgressing;
    case Ipopt::DIVERGING_ITERATES: return Termination::kNotProgressing;
    case Ipopt::RESTORATION_FAILURE: return Termination::kNotProgressing;
    case Ipopt::USER_REQUESTED_STOP: return Termination::kConverged;  // refined by the stop reason
    case Ipopt::INVALID_NUMBER_DETECTED: return Termination::kEvaluationFailed;
    case Ipopt::TOO_FEW_DEGREES_OF_FREEDOM: return Termination::kInvalidOptions;
    case Ipopt::INVALID_OPTION: return Termination::kInvalidOptions;
    case Ipopt::ERROR_IN_STEP_COMPUTATION:
    case Ipopt::OUT_OF_MEMORY:
    case Ipopt::INTERNAL_ERROR:
    case Ipopt::UNASSIGNED: return Termination::kBackendError;
  }
  return Termination::kBackendError;
}

void IpoptBackend::run(MonitoredSystem& system, const Eigen::VectorXd& z0,
                       const SolverOptions& options, SolverResult& result) {
  bool gauss_newton = true;
  for (const auto& [key, text] : options.backend) {
    if (key == "hessian" && formulation_ == IpoptFormulation::kLeastSquares &&
        (text == "gauss-newton" || text == "limited-memory")) {
      gauss_newton = text == "gauss-newton";
    } else {
      result.termination = Termination::kInvalidOptions;
      result.native_message = "unknown or invalid ipopt option \"" + key + "\" = \"" + text +
                              "\" (known: hessian=gauss-newton|limited-memory for ipopt-ls)";
      return;
    }
  }
  const bool least_squares = formulation_ == IpoptFormulation::kLeastSquares;
  const bool sparse = useSparseAlgebra(system, options);
  if (!sparse && !denseBackendAccepts(name() + " (dense Jacobian)", system.size(),
                                      kDenseMostUnknowns, options, result))
    return;
  Ipopt::SmartPtr<SystemNlp> nlp =
      new SystemNlp(system, options, z0, least_squares, least_squares && gauss_newton, sparse);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Options()->SetStringValue("sb", "yes");
  app->Options()->SetIntegerValue("print_level", 0);
  app->Options()->SetIntegerValue("max_iter", options.max_iterations);
  app->Options()->SetNumericValue("tol", 1e-14);
  app->Options()->SetNumericValue("acceptable_tol", 1e-14);
  app->Options()->SetNumericValue("constr_viol_tol", 1e-14);
  if (!(least_squares && gauss_newton))
    app->Options()->SetStringValue("hessian_approximation", "limited-memory");
  if (options.time_limit > 0.0) app->Options()->SetNumericValue("max_cpu_time", options.time_limit);
  if (app->Initialize() != Ipopt::Solve_Succeeded) {
    result.termination = Termination::kBackendError;
    result.native_message = "Ipopt failed to initialise";
    return;
  }
  app->OptimizeTNLP(nlp);

  result.native_code = nlp->status();
  result.native_message = std::string(solverReturnName(nlp->status())) +
                          (sparse ? " (sparse Jacobian, MUMPS)" : "");
  result.termination = ipoptTermination(nlp->status());
  result.iterations = nlp->iterations;
  if (nlp->accepted.size() > 0) {
    result.solution = nlp->accepted;
    result.termination = Termination::kConverged;
  } else {
    if (nlp->status() == Ipopt::USER_REQUESTED_STOP) result.termination = nlp->stop_reason;
    if (!nlp->final().empty())
      result.solution = Eigen::Map<const Eigen::VectorXd>(nlp->final().data(), system.size());
  }
}

}  // namespace eqhb
