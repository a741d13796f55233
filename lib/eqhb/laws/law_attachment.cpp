#include "eqhb/laws/law_attachment.h"

#include <cmath>
#include <set>

#include "eqhb/error.h"

namespace eqhb {

LawAttachment::LawAttachment(std::vector<int> dofs) {
  rows_.reserve(dofs.size());
  for (int dof : dofs) rows_.push_back({AttachmentTerm{dof, 1.0}});
  index();
}

LawAttachment::LawAttachment(std::vector<std::vector<AttachmentTerm>> rows) : rows_(std::move(rows)) { index(); }

LawAttachment LawAttachment::relative(const std::vector<int>& p, const std::vector<int>& q,
                                      const std::vector<Eigen::VectorXd>& directions) {
  std::vector<std::vector<AttachmentTerm>> rows;
  for (const Eigen::VectorXd& n : directions) {
    std::vector<AttachmentTerm> row;
    for (size_t i = 0; i < p.size(); ++i)
      if (n[static_cast<Eigen::Index>(i)] != 0.0) row.push_back({p[i], n[static_cast<Eigen::Index>(i)]});
    for (size_t i = 0; i < q.size(); ++i)
      if (n[static_cast<Eigen::Index>(i)] != 0.0) row.push_back({q[i], -n[static_cast<Eigen::Index>(i)]});
    rows.push_back(row);
  }
  return LawAttachment(std::move(rows));
}

void LawAttachment::index() {
  grounded_ = true;
  dofs_.clear();
  std::set<int> seen;
  for (const auto& r : rows_) {
    if (r.size() != 1 || r.front().weight != 1.0) grounded_ = false;
    for (const auto& term : r)
      if (seen.insert(term.dof).second) dofs_.push_back(term.dof);
  }
}

std::string LawAttachment::describe() const {
  std::string text = "[";
  for (size_t a = 0; a < rows_.size(); ++a) {
    if (a) text += ", ";
    if (grounded_) {
      text += std::to_string(rows_[a].front().dof + 1);
      continue;
    }
    for (size_t k = 0; k < rows_[a].size(); ++k) {  // "x1 - x4", "0.6 x1 + 0.8 x2"
      const double w = rows_[a][k].weight;
      if (k) text += w < 0.0 ? " - " : " + ";
      else if (w < 0.0) text += "-";
      if (std::abs(w) != 1.0) text += formatNumber(std::abs(w)) + " ";
      text += "x" + std::to_string(rows_[a][k].dof + 1);
    }
  }
  return text + "]";
}

void LawAttachment::gatherCoefficients(const double* x, int stride, int a, double* out) const {
  const auto& r = rows_[a];
  const double* first = x + static_cast<std::ptrdiff_t>(r.front().dof) * stride;
  const double w0 = r.front().weight;
  for (int t = 0; t < stride; ++t) out[t] = w0 * first[t];
  for (size_t k = 1; k < r.size(); ++k) {
    const double* xk = x + static_cast<std::ptrdiff_t>(r[k].dof) * stride;
    const double w = r[k].weight;
    for (int t = 0; t < stride; ++t) out[t] += w * xk[t];
  }
}

void LawAttachment::scatterCoefficients(const double* values, int stride, int a, double scale, double* y) const {
  for (const auto& term : rows_[a]) {
    double* yk = y + static_cast<std::ptrdiff_t>(term.dof) * stride;
    const double w = scale * term.weight;
    for (int t = 0; t < stride; ++t) yk[t] += w * values[t];
  }
}

Eigen::MatrixXd LawAttachment::transposeDense(int n, double scale) const {
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(n, dimension());
  for (int a = 0; a < dimension(); ++a)
    for (const auto& term : rows_[a]) w(term.dof, a) += scale * term.weight;
  return w;
}

Eigen::RowVectorXd LawAttachment::rowTimes(const Eigen::MatrixXd& y, int a) const {
  const auto& r = rows_[a];
  Eigen::RowVectorXd out = r.front().weight * y.row(r.front().dof);
  for (size_t k = 1; k < r.size(); ++k) out += r[k].weight * y.row(r[k].dof);
  return out;
}

void LawAttachment::validate(int n, const std::string& field) const {
  std::set<int> distinct;
  for (size_t a = 0; a < rows_.size(); ++a) {
    if (rows_[a].empty()) throwInputError(field, describe(), "component " + std::to_string(a + 1) + " reads no DOF");
    std::set<int> in_row;
    for (const auto& term : rows_[a]) {
      if (term.dof < 0 || term.dof >= n)
        throwInputError(field, std::to_string(term.dof + 1),
                        "no such DOF (the structure has " + std::to_string(n) + ", numbered from 1)");
      if (!std::isfinite(term.weight)) throwInputError(field, formatNumber(term.weight), "a weight must be finite");
      if (!in_row.insert(term.dof).second || (grounded_ && !distinct.insert(term.dof).second))
        throwInputError(field, std::to_string(term.dof + 1), "listed twice");
    }
  }
}

}  // namespace eqhb
