#include "free_set_factor.h"

#include <cholmod.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace fibrecheck {

namespace {

/// A factor is made afresh rather than modified where more variables changed than this, plus a
/// fiftieth of the free ones: a row added or deleted costs a small part of a factorisation.
constexpr std::size_t kModificationsAtOnce = 32;
/// An answer is at round-off when its residual is within this of ‖|W_FF|·|x| + |b|‖∞.
constexpr double kRoundOff = 1e-11;

/// A CHOLMOD view of a compressed, symmetric Eigen matrix (its upper triangle is read).
cholmod_sparse view_of(Eigen::SparseMatrix<double>& A) {
  A.makeCompressed();
  cholmod_sparse s{};
  s.nrow = static_cast<std::size_t>(A.rows());
  s.ncol = static_cast<std::size_t>(A.cols());
  s.nzmax = static_cast<std::size_t>(A.nonZeros());
  s.p = A.outerIndexPtr();
  s.i = A.innerIndexPtr();
  s.x = A.valuePtr();
  s.stype = 1;
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

}  // namespace

/// One simplicial LDLᵀ factor of W_FF + shift·I, identity outside F, in CHOLMOD.
class FreeSetFactor::Factor {
 public:
  Factor(const Eigen::SparseMatrix<double>& W, double shift) : W_(W), shift_(shift) {
    cholmod_start(&common_);
    common_.print = 0;
    common_.supernodal = CHOLMOD_SIMPLICIAL;
    common_.final_ll = 0;
    common_.nmethods = 1;
    common_.method[0].ordering = CHOLMOD_AMD;
    position_.assign(static_cast<std::size_t>(W.rows()), 0);
  }
  ~Factor() {
    if (L_) cholmod_free_factor(&L_, &common_);
    cholmod_finish(&common_);
  }
  Factor(const Factor&) = delete;
  Factor& operator=(const Factor&) = delete;

  /// The factor brought to F, by modifications or made afresh (where asked, where it has none or
  /// where F is far from it): false where it broke down.
  bool bring_to(const std::vector<char>& free, bool afresh, int& factorisations,
                int& modifications) {
    std::size_t changed = 0, count = 0;
    for (std::size_t j = 0; j < free.size(); ++j) {
      count += free[j] ? 1 : 0;
      changed += valid_ && factored_[j] != free[j] ? 1 : 0;
    }
    modified_ = !(afresh || !valid_ || changed > kModificationsAtOnce + count / 50);
    if (!modified_) {
      ++factorisations;
      return refactor(free);
    }
    modifications += static_cast<int>(changed);
    return modify(free);
  }

  bool modified() const { return modified_; }
  double shift() const { return shift_; }

  /// Every pivot of F positive and none below 1e-14 of the largest (subset_solve.h).
  bool pivots_sound() const {
    const auto [smallest, largest] = pivot_extremes();
    return !std::isnan(smallest) && (smallest == INFINITY || smallest > 1e-14 * largest);
  }

  /// The smallest pivot of F over the largest (a rough reciprocal condition of W_FF).
  double pivot_ratio() const {
    if (!valid_ || !L_) return 1.0;
    const auto [smallest, largest] = pivot_extremes();
    return largest > 0.0 && std::isfinite(smallest) ? std::fabs(smallest) / largest : 1.0;
  }

  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
    cholmod_dense B{};
    B.nrow = static_cast<std::size_t>(b.size());
    B.ncol = 1;
    B.nzmax = B.nrow;
    B.d = B.nrow;
    B.x = const_cast<double*>(b.data());
    B.xtype = CHOLMOD_REAL;
    B.dtype = CHOLMOD_DOUBLE;
    cholmod_dense* X = cholmod_solve(CHOLMOD_A, L_, &B, &common_);
    if (X == nullptr) return false;
    x = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(X->x), b.size());
    cholmod_free_dense(&X, &common_);
    return x.allFinite();
  }

 private:
  // W_FF + shift·I with identity rows and columns outside F, ordered (AMD on its own pattern: the
  // variables that join F later take the places it gives them) and factorised.
  bool refactor(const std::vector<char>& free) {
    factored_ = free;
    valid_ = false;
    if (L_) cholmod_free_factor(&L_, &common_);
    Eigen::SparseMatrix<double> masked = upper_masked(free);
    cholmod_sparse A = view_of(masked);
    L_ = cholmod_analyze(&A, &common_);
    if (L_ == nullptr) return false;
    const int* perm = static_cast<const int*>(L_->Perm);
    for (std::size_t k = 0; k < position_.size(); ++k) position_[perm[k]] = static_cast<int>(k);
    cholmod_factorize(&A, L_, &common_);
    valid_ = common_.status == CHOLMOD_OK && !L_->is_super && !L_->is_ll;
    return valid_;
  }

  // The upper triangle of W_FF + shift·I, identity outside F, column by column.
  Eigen::SparseMatrix<double> upper_masked(const std::vector<char>& free) const {
    const Eigen::Index n = W_.rows();
    Eigen::SparseMatrix<double> masked(n, n);
    Eigen::VectorXi count(n);
    for (Eigen::Index j = 0; j < n; ++j) {
      count[j] = 1;
      if (free[j])
        for (Eigen::SparseMatrix<double>::InnerIterator it(W_, j); it && it.row() < j; ++it)
          count[j] += free[it.row()] ? 1 : 0;
    }
    masked.reserve(count);
    for (Eigen::Index j = 0; j < n; ++j) {
      if (free[j])
        for (Eigen::SparseMatrix<double>::InnerIterator it(W_, j); it && it.row() < j; ++it)
          if (free[it.row()]) masked.insert(it.row(), j) = it.value();
      masked.insert(j, j) = free[j] ? W_.coeff(j, j) + shift_ : 1.0;
    }
    masked.makeCompressed();
    return masked;
  }

  // The variables that left F deleted from the factor, then those that joined it added.
  bool modify(const std::vector<char>& free) {
    const Eigen::Index n = W_.rows();
    for (Eigen::Index j = 0; j < n; ++j)
      if (factored_[j] && !free[j]) {
        factored_[j] = 0;
        if (!cholmod_rowdel(static_cast<std::size_t>(position_[j]), nullptr, L_, &common_))
          return valid_ = false;
      }
    std::vector<std::pair<int, double>> column;
    std::vector<int> p{0, 0}, rows;
    std::vector<double> values;
    for (Eigen::Index j = 0; j < n; ++j) {
      if (factored_[j] || !free[j]) continue;
      factored_[j] = 1;
      column.clear();
      for (Eigen::SparseMatrix<double>::InnerIterator it(W_, j); it; ++it)
        if (factored_[it.row()])
          column.emplace_back(position_[it.row()], it.value() + (it.row() == j ? shift_ : 0.0));
      std::sort(column.begin(), column.end());
      rows.clear();
      values.clear();
      for (const auto& [row, value] : column) rows.push_back(row), values.push_back(value);
      p[1] = static_cast<int>(rows.size());
      rows.resize(std::max<std::size_t>(rows.size(), 1), 0);
      values.resize(rows.size(), 0.0);
      cholmod_sparse R{};
      R.nrow = static_cast<std::size_t>(n);
      R.ncol = 1;
      R.nzmax = rows.size();
      R.p = p.data();
      R.i = rows.data();
      R.x = values.data();
      R.itype = CHOLMOD_INT;
      R.xtype = CHOLMOD_REAL;
      R.dtype = CHOLMOD_DOUBLE;
      R.sorted = 1;
      R.packed = 1;
      if (!cholmod_rowadd(static_cast<std::size_t>(position_[j]), &R, L_, &common_))
        return valid_ = false;
    }
    return valid_;
  }

  /// The smallest and largest pivot of F (NaN for the smallest where one is not finite).
  std::pair<double, double> pivot_extremes() const {
    const int* p = static_cast<const int*>(L_->p);
    const double* x = static_cast<const double*>(L_->x);
    double smallest = INFINITY, largest = 0.0;
    for (std::size_t j = 0; j < factored_.size(); ++j) {
      if (!factored_[j]) continue;
      const double d = x[p[position_[j]]];
      if (!std::isfinite(d)) return {NAN, largest};
      smallest = std::min(smallest, d);
      largest = std::max(largest, d);
    }
    return {smallest, largest};
  }

  const Eigen::SparseMatrix<double>& W_;
  const double shift_;
  cholmod_common common_{};
  cholmod_factor* L_ = nullptr;
  std::vector<int> position_;   ///< per variable, its row in the factor (the ordering's inverse)
  std::vector<char> factored_;  ///< the free set the factor holds
  bool valid_ = false;
  bool modified_ = false;  ///< brought to the present set by modifications
};

FreeSetFactor::FreeSetFactor(const Eigen::SparseMatrix<double>& W)
    : W_(W),
      epsilon_(W.rows() > 0 ? 1e-10 * W.diagonal().cwiseAbs().maxCoeff() : 0.0),
      exact_(std::make_unique<Factor>(W, 0.0)) {}

FreeSetFactor::~FreeSetFactor() = default;

// ‖b − (W + shift·I)·x‖∞ / ‖|W + shift·I|·|x| + |b|‖∞ over F, x zero outside F.
double FreeSetFactor::residual_ratio(const std::vector<char>& free, const Eigen::VectorXd& b,
                                     const Eigen::VectorXd& x, double shift) const {
  const Eigen::Index n = W_.rows();
  Eigen::VectorXd residual = b - shift * x, scale = b.cwiseAbs() + shift * x.cwiseAbs();
  for (Eigen::Index j = 0; j < n; ++j) {
    if (!free[j] || x[j] == 0.0) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(W_, j); it; ++it) {
      residual[it.row()] -= it.value() * x[j];
      scale[it.row()] += std::fabs(it.value() * x[j]);
    }
  }
  double largest = 0.0, size = 0.0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (free[i])
      largest = std::max(largest, std::fabs(residual[i])), size = std::max(size, scale[i]);
  return size > 0.0 ? largest / size : 0.0;
}

// The factor's answer where its residual is at round-off (or unjudged); one made afresh where a
// modified one's is not.
bool FreeSetFactor::solve_with(Factor& factor, const std::vector<char>& free,
                               const Eigen::VectorXd& b, Eigen::VectorXd& x, bool judged) {
  last_shift_ = factor.shift();
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (attempt == 1 &&
        (!factor.modified() || !factor.bring_to(free, true, factorisations_, modifications_)))
      return false;
    if (factor.solve(b, x) && (!judged || residual_ratio(free, b, x, factor.shift()) <= kRoundOff))
      return true;
  }
  return false;
}

bool FreeSetFactor::solve(const std::vector<char>& free, const Eigen::VectorXd& b,
                          Eigen::VectorXd& x, bool judged) {
  Eigen::VectorXd masked = b;
  for (std::size_t j = 0; j < free.size(); ++j)
    if (!free[j]) masked[static_cast<Eigen::Index>(j)] = 0.0;
  if (exact_->bring_to(free, false, factorisations_, modifications_) && exact_->pivots_sound())
    return solve_with(*exact_, free, masked, x, judged);
  if (!regularised_) regularised_ = std::make_unique<Factor>(W_, epsilon_);
  return regularised_->bring_to(free, false, factorisations_, modifications_) &&
         solve_with(*regularised_, free, masked, x, judged);
}

double FreeSetFactor::pivot_ratio() const {
  return last_shift_ > 0.0 && regularised_ ? regularised_->pivot_ratio() : exact_->pivot_ratio();
}

bool FreeSetFactor::answers(const std::vector<char>& free, const Eigen::VectorXd& b,
                            const Eigen::VectorXd& x) const {
  return residual_ratio(free, b, x, last_shift_) <= kRoundOff;
}

}  // namespace fibrecheck
