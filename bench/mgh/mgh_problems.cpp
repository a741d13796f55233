#include "mgh_problems.h"

#include <cmath>
#include <sstream>
#include <unsupported/Eigen/AutoDiff>

namespace eqhb::mgh {

namespace {

using Dual = Eigen::AutoDiffScalar<Eigen::VectorXd>;

// f(x) for problem `p`, written once for double and for Dual; 0-based
// transcription of the MGH definitions.
template <typename T>
void evaluate(int p, int n, const std::vector<T>& x, std::vector<T>& f) {
  using std::cos;
  using std::exp;
  using std::sin;
  using std::sqrt;
  const T zero = x[0] * 0.0;
  for (auto& v : f) v = zero;
  switch (p) {
    case 1:  // Rosenbrock
      f[0] = 1.0 - x[0];
      f[1] = 10.0 * (x[1] - x[0] * x[0]);
      break;
    case 2: {  // Powell singular
      f[0] = x[0] + 10.0 * x[1];
      f[1] = std::sqrt(5.0) * (x[2] - x[3]);
      const T a = x[1] - 2.0 * x[2];
      f[2] = a * a;
      const T b = x[0] - x[3];
      f[3] = std::sqrt(10.0) * b * b;
      break;
    }
    case 3:  // Powell badly scaled
      f[0] = 1e4 * x[0] * x[1] - 1.0;
      f[1] = exp(-x[0]) + exp(-x[1]) - 1.0001;
      break;
    case 4: {  // Wood (gradient form)
      const T c = x[1] - x[0] * x[0], d = x[3] - x[2] * x[2];
      f[0] = -200.0 * x[0] * c - (1.0 - x[0]);
      f[1] = 200.0 * c + 20.2 * (x[1] - 1.0) + 19.8 * (x[3] - 1.0);
      f[2] = -180.0 * x[2] * d - (1.0 - x[2]);
      f[3] = 180.0 * d + 20.2 * (x[3] - 1.0) + 19.8 * (x[1] - 1.0);
      break;
    }
    case 5: {  // helical valley; θ in (−1/4, 3/4] turns, as MINPACK's branch
      using std::atan2;
      T theta = atan2(x[1], x[0]);
      if (x[0] < 0.0 && x[1] < 0.0) theta = theta + 2.0 * M_PI;
      f[0] = 10.0 * (x[2] - 10.0 * theta / (2.0 * M_PI));
      f[1] = 10.0 * (sqrt(x[0] * x[0] + x[1] * x[1]) - 1.0);
      f[2] = x[2];
      break;
    }
    case 6: {  // Watson (gradient of the least-squares function)
      for (int i = 1; i <= 29; ++i) {
        const double ti = i / 29.0;
        T s1 = zero, s2 = zero;
        double power = 1.0;
        for (int j = 1; j < n; ++j) {
          s1 = s1 + double(j) * power * x[j];
          power *= ti;
        }
        power = 1.0;
        for (int j = 0; j < n; ++j) {
          s2 = s2 + power * x[j];
          power *= ti;
        }
        const T t1 = s1 - s2 * s2 - 1.0;
        const T t2 = 2.0 * ti * s2;
        double weight = 1.0 / ti;
        for (int k = 0; k < n; ++k) {
          f[k] = f[k] + weight * (double(k) - t2) * t1;
          weight *= ti;
        }
      }
      const T t = x[1] - x[0] * x[0] - 1.0;
      f[0] = f[0] + x[0] * (1.0 - 2.0 * t);
      f[1] = f[1] + t;
      break;
    }
    case 7: {  // Chebyquad
      for (int j = 0; j < n; ++j) {
        T t_prev = zero + 1.0, t_cur = 2.0 * x[j] - 1.0;
        const T two_y = 2.0 * t_cur;
        for (int i = 0; i < n; ++i) {
          f[i] = f[i] + t_cur;
          const T t_next = two_y * t_cur - t_prev;
          t_prev = t_cur;
          t_cur = t_next;
        }
      }
      for (int i = 0; i < n; ++i) {
        f[i] = f[i] / double(n);
        const int degree = i + 1;
        if (degree % 2 == 0) f[i] = f[i] + 1.0 / (degree * degree - 1.0);
      }
      break;
    }
    case 8: {  // Brown almost-linear
      T sum = zero - double(n + 1), prod = zero + 1.0;
      for (int j = 0; j < n; ++j) {
        sum = sum + x[j];
        prod = prod * x[j];
      }
      for (int i = 0; i < n; ++i) f[i] = x[i] + sum;
      f[n - 1] = prod - 1.0;
      break;
    }
    case 9: {  // discrete boundary value
      const double h = 1.0 / (n + 1);
      for (int k = 0; k < n; ++k) {
        const T a = x[k] + (k + 1) * h + 1.0;
        const T left = k > 0 ? x[k - 1] : zero;
        const T right = k + 1 < n ? x[k + 1] : zero;
        f[k] = 2.0 * x[k] - left - right + a * a * a * (h * h / 2.0);
      }
      break;
    }
    case 10: {  // discrete integral equation
      const double h = 1.0 / (n + 1);
      for (int k = 0; k < n; ++k) {
        const double tk = (k + 1) * h;
        T below = zero, above = zero;
        for (int j = 0; j < n; ++j) {
          const double tj = (j + 1) * h;
          const T a = x[j] + tj + 1.0;
          if (j <= k) below = below + tj * a * a * a;
          else above = above + (1.0 - tj) * a * a * a;
        }
        f[k] = x[k] + h * ((1.0 - tk) * below + tk * above) / 2.0;
      }
      break;
    }
    case 11: {  // trigonometric
      T sum = zero;
      for (int j = 0; j < n; ++j) sum = sum + cos(x[j]);
      for (int k = 0; k < n; ++k)
        f[k] = double(n + k + 1) - sin(x[k]) - sum - double(k + 1) * cos(x[k]);
      break;
    }
    case 12: {  // variably dimensioned
      T sum = zero;
      for (int j = 0; j < n; ++j) sum = sum + double(j + 1) * (x[j] - 1.0);
      const T t = sum * (1.0 + 2.0 * sum * sum);
      for (int k = 0; k < n; ++k) f[k] = x[k] - 1.0 + double(k + 1) * t;
      break;
    }
    case 13:  // Broyden tridiagonal
      for (int k = 0; k < n; ++k) {
        const T left = k > 0 ? x[k - 1] : zero;
        const T right = k + 1 < n ? x[k + 1] : zero;
        f[k] = (3.0 - 2.0 * x[k]) * x[k] - left - 2.0 * right + 1.0;
      }
      break;
    case 14:  // Broyden banded (ml = 5, mu = 1)
      for (int k = 0; k < n; ++k) {
        T sum = zero;
        for (int j = std::max(0, k - 5); j <= std::min(n - 1, k + 1); ++j)
          if (j != k) sum = sum + x[j] * (1.0 + x[j]);
        f[k] = x[k] * (2.0 + 5.0 * x[k] * x[k]) + 1.0 - sum;
      }
      break;
  }
}

}  // namespace

std::string problemName(int problem) {
  static const char* names[] = {"Rosenbrock", "Powell singular", "Powell badly scaled", "Wood",
                                "helical valley", "Watson", "Chebyquad", "Brown almost-linear",
                                "discrete boundary value", "discrete integral equation",
                                "trigonometric", "variably dimensioned", "Broyden tridiagonal",
                                "Broyden banded"};
  return problem >= 1 && problem <= 14 ? names[problem - 1] : "?";
}

Eigen::VectorXd startingPoint(int problem, int n, double factor) {
  Eigen::VectorXd x(n);
  const double h = 1.0 / (n + 1);
  switch (problem) {
    case 1: x << -1.2, 1.0; break;
    case 2: x << 3.0, -1.0, 0.0, 1.0; break;
    case 3: x << 0.0, 1.0; break;
    case 4: x << -3.0, -1.0, -3.0, -1.0; break;
    case 5: x << -1.0, 0.0, 0.0; break;
    case 6: x.setZero(); break;
    case 7: for (int j = 0; j < n; ++j) x[j] = (j + 1) * h; break;
    case 8: x.setConstant(0.5); break;
    case 9:
    case 10:
      for (int j = 0; j < n; ++j) x[j] = (j + 1) * h * ((j + 1) * h - 1.0);
      break;
    case 11: x.setConstant(1.0 / n); break;
    case 12: for (int j = 0; j < n; ++j) x[j] = 1.0 - (j + 1.0) / n; break;
    case 13:
    case 14: x.setConstant(-1.0); break;
  }
  if (factor == 1.0) return x;
  if (problem == 6) return Eigen::VectorXd::Constant(n, factor);
  return factor * x;
}

MghSystem::MghSystem(int problem, int n) : problem_(problem), n_(n) {}

bool MghSystem::residual(const Eigen::Ref<const Eigen::VectorXd>& z,
                         Eigen::Ref<Eigen::VectorXd> g) {
  std::vector<double> x(z.data(), z.data() + n_), f(n_);
  evaluate(problem_, n_, x, f);
  for (int i = 0; i < n_; ++i) g[i] = f[i];
  return g.allFinite();
}

bool MghSystem::residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                                    Eigen::Ref<Eigen::VectorXd> g,
                                    Eigen::Ref<Eigen::MatrixXd> jacobian) {
  std::vector<Dual> x(n_), f(n_);
  for (int j = 0; j < n_; ++j) x[j] = Dual(z[j], n_, j);
  evaluate(problem_, n_, x, f);
  for (int i = 0; i < n_; ++i) {
    g[i] = f[i].value();
    if (f[i].derivatives().size() == n_) jacobian.row(i) = f[i].derivatives().transpose();
    else jacobian.row(i).setZero();  // a constant component carries no derivatives
  }
  return g.allFinite() && jacobian.allFinite();
}

std::vector<Case> standardCases() {
  const int pairs[][2] = {{1, 2},  {2, 4},   {3, 2},   {4, 4},  {5, 3},   {6, 6},
                          {6, 9},  {7, 5},   {7, 6},   {7, 7},  {7, 8},   {7, 9},
                          {8, 10}, {8, 30},  {8, 40},  {9, 10}, {10, 1},  {10, 10},
                          {11, 10}, {12, 10}, {13, 10}, {14, 10}};
  std::vector<Case> cases;
  for (const auto& pair : pairs)
    for (double factor : {1.0, 10.0, 100.0}) cases.push_back({pair[0], pair[1], factor});
  return cases;
}

namespace {
Outcome runOne(Solver& solver, const Case& c, const std::map<std::string, std::string>& backend) {
  MghSystem system(c.problem, c.n);
  SolverOptions options;
  options.residual_tolerance = 0.0;  // MINPACK's own criteria only
  options.max_evaluations = 100 * (c.n + 1);
  options.max_iterations = 1000000;
  options.backend["xtol"] = "1.4901161193847656e-08";  // sqrt(eps), as hybrj1
  options.backend["factor"] = "100";
  for (const auto& [key, value] : backend) options.backend[key] = value;
  const SolverResult r = solver.solve(system, startingPoint(c.problem, c.n, c.factor), options);
  Outcome o;
  o.final_norm = r.final_norm;
  o.solved = std::isfinite(r.final_norm) && r.final_norm <= kSolvedNorm;
  o.termination = terminationName(r.termination);
  o.native_code = r.native_code;
  o.residual_evaluations = r.residual_evaluations;
  o.jacobian_evaluations = r.jacobian_evaluations;
  return o;
}
}  // namespace

std::vector<Row> compare(Solver& own, Solver& reference, const std::vector<Case>& cases,
                         const std::map<std::string, std::string>& own_backend,
                         const std::map<std::string, std::string>& reference_backend) {
  std::vector<Row> rows;
  for (const Case& c : cases) rows.push_back({c, runOne(own, c, own_backend), runOne(reference, c, reference_backend)});
  return rows;
}

std::string markdownTable(const std::vector<Row>& rows) {
  std::ostringstream out;
  out << "| # | problem | n | start | own solved | own nfev | own njev | own ‖f‖ | MINPACK solved | "
         "MINPACK nfev | MINPACK njev | MINPACK ‖f‖ | MINPACK info |\n"
      << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  int own_solved = 0, ref_solved = 0, both = 0, only_ref = 0;
  for (const Row& r : rows) {
    out << "| " << r.test.problem << " | " << problemName(r.test.problem) << " | " << r.test.n
        << " | ×" << r.test.factor << " | " << (r.own.solved ? "yes" : "NO") << " | "
        << r.own.residual_evaluations << " | " << r.own.jacobian_evaluations << " | "
        << r.own.final_norm << " | " << (r.reference.solved ? "yes" : "NO") << " | "
        << r.reference.residual_evaluations << " | " << r.reference.jacobian_evaluations << " | "
        << r.reference.final_norm << " | " << r.reference.native_code << " |\n";
    own_solved += r.own.solved;
    ref_solved += r.reference.solved;
    both += r.own.solved && r.reference.solved;
    only_ref += r.reference.solved && !r.own.solved;
  }
  out << "\nSolved (‖f‖ <= " << kSolvedNorm << "): own " << own_solved << "/" << rows.size()
      << ", MINPACK " << ref_solved << "/" << rows.size() << ", both " << both
      << ", MINPACK only " << only_ref << "\n";
  return out.str();
}

}  // namespace eqhb::mgh
