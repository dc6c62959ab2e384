#pragma once
// A scalar for reverse-mode (adjoint) differentiation of the templated EKF (ml_ekf.hpp,
// ml_likelihood.hpp): every operation on it appends one node to a tape (its value and the
// partial derivatives with respect to at most two operands), and one backward sweep over
// the tape gives the derivatives of an output with respect to every input at once.
//
// Why: forward-mode Jets carry 34 derivatives through every operation of the EKF, forward
// differences need 35 evaluations; a sweep back costs a small multiple of one evaluation
// whatever the number of parameters. ml_adjoint_gradient.cpp records one EKF step at a time
// so that the tape stays in the cache.
//
// Constants (anything made from a double) are not on the tape (index kConstant) and cost
// no node. The tape is per thread and must be active (ReverseTapeScope) while the scalars
// are used.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Core>

namespace headingd::calib {

struct ReverseTapeNode {
  std::int32_t parent_a = 0;  // 0 is the tape's sink node: an operand that is a constant
  std::int32_t parent_b = 0;
  double partial_a = 0.0;
  double partial_b = 0.0;
};

class ReverseTape {
 public:
  // Empties the tape but keeps its memory (one calibration records thousands of tapes).
  void clear() { count_ = 1; }  // node 0 is the sink
  [[gnu::always_inline]] std::int32_t push(std::int32_t a, double da, std::int32_t b, double db) {
    if (count_ == nodes_.size()) grow();
    nodes_[count_] = ReverseTapeNode{a, b, da, db};
    return static_cast<std::int32_t>(count_++);
  }
  std::size_t size() const { return count_; }

  // The backward sweep: seed d output / d node for the outputs (zero elsewhere), sweep, read
  // d output / d node of the inputs. Seeding a constant does nothing (nothing depends on it).
  void clearAdjoints() { adjoints_.assign(count_, 0.0); }
  void seed(std::int32_t index, double adjoint) {
    if (index > 0) adjoints_[static_cast<std::size_t>(index)] += adjoint;
  }
  void sweepBack() {
    for (std::size_t i = count_ - 1; i > 0; --i) {
      const double w = adjoints_[i];
      const ReverseTapeNode& n = nodes_[i];
      adjoints_[static_cast<std::size_t>(n.parent_a)] += n.partial_a * w;
      adjoints_[static_cast<std::size_t>(n.parent_b)] += n.partial_b * w;
    }
  }
  double adjoint(std::int32_t index) const { return index > 0 ? adjoints_[static_cast<std::size_t>(index)] : 0.0; }

  // The tape the scalars of this thread record on.
  [[gnu::always_inline]] static ReverseTape*& active() {
    thread_local ReverseTape* tape = nullptr;
    return tape;
  }

 private:
  void grow() { nodes_.resize(std::max<std::size_t>(2 * nodes_.size(), 4096)); }

  std::vector<ReverseTapeNode> nodes_ = std::vector<ReverseTapeNode>(4096);
  std::size_t count_ = 1;
  std::vector<double> adjoints_;
};

// Makes `tape` the thread's active tape (cleared) for its lifetime.
class ReverseTapeScope {
 public:
  explicit ReverseTapeScope(ReverseTape& tape) : previous_(ReverseTape::active()) {
    tape.clear();
    ReverseTape::active() = &tape;
  }
  ~ReverseTapeScope() { ReverseTape::active() = previous_; }
  ReverseTapeScope(const ReverseTapeScope&) = delete;
  ReverseTapeScope& operator=(const ReverseTapeScope&) = delete;

 private:
  ReverseTape* previous_;
};

class ReverseScalar {
 public:
  static constexpr std::int32_t kConstant = -1;

  ReverseScalar() = default;
  // Implicit on purpose: Eigen and the EKF write constants as T(0.5), Scalar(1), ...
  ReverseScalar(double value) : value_(value) {}  // NOLINT(google-explicit-constructor)

  // An independent variable: a node without parents.
  static ReverseScalar variable(double value) {
    return ReverseScalar(value, ReverseTape::active()->push(0, 0.0, 0, 0.0));
  }

  double value() const { return value_; }
  std::int32_t index() const { return index_; }
  bool isConstant() const { return index_ == kConstant; }

  // f(x) with f'(x) = d.
  [[gnu::always_inline]] static ReverseScalar unary(double value, const ReverseScalar& x, double d) {
    if (x.isConstant()) return ReverseScalar(value);
    return ReverseScalar(value, ReverseTape::active()->push(x.index_, d, 0, 0.0));
  }
  // f(x, y) with ∂f/∂x = dx, ∂f/∂y = dy.
  [[gnu::always_inline]] static ReverseScalar binary(double value, const ReverseScalar& x, double dx,
                                                     const ReverseScalar& y, double dy) {
    if (x.isConstant()) return unary(value, y, dy);
    if (y.isConstant()) return unary(value, x, dx);
    return ReverseScalar(value, ReverseTape::active()->push(x.index_, dx, y.index_, dy));
  }

  [[gnu::always_inline]] friend ReverseScalar operator+(const ReverseScalar& x, const ReverseScalar& y) {
    return binary(x.value_ + y.value_, x, 1.0, y, 1.0);
  }
  [[gnu::always_inline]] friend ReverseScalar operator-(const ReverseScalar& x, const ReverseScalar& y) {
    return binary(x.value_ - y.value_, x, 1.0, y, -1.0);
  }
  [[gnu::always_inline]] friend ReverseScalar operator*(const ReverseScalar& x, const ReverseScalar& y) {
    return binary(x.value_ * y.value_, x, y.value_, y, x.value_);
  }
  [[gnu::always_inline]] friend ReverseScalar operator/(const ReverseScalar& x, const ReverseScalar& y) {
    const double inv = 1.0 / y.value_;
    const double q = x.value_ * inv;
    return binary(q, x, inv, y, -q * inv);
  }
  friend ReverseScalar operator-(const ReverseScalar& x) { return unary(-x.value_, x, -1.0); }
  friend ReverseScalar operator+(const ReverseScalar& x) { return x; }

  ReverseScalar& operator+=(const ReverseScalar& y) { return *this = *this + y; }
  ReverseScalar& operator-=(const ReverseScalar& y) { return *this = *this - y; }
  ReverseScalar& operator*=(const ReverseScalar& y) { return *this = *this * y; }
  ReverseScalar& operator/=(const ReverseScalar& y) { return *this = *this / y; }

  // Comparisons look at the values only (the branch taken is the one differentiated).
  friend bool operator<(const ReverseScalar& x, const ReverseScalar& y) { return x.value_ < y.value_; }
  friend bool operator>(const ReverseScalar& x, const ReverseScalar& y) { return x.value_ > y.value_; }
  friend bool operator<=(const ReverseScalar& x, const ReverseScalar& y) { return x.value_ <= y.value_; }
  friend bool operator>=(const ReverseScalar& x, const ReverseScalar& y) { return x.value_ >= y.value_; }
  friend bool operator==(const ReverseScalar& x, const ReverseScalar& y) { return x.value_ == y.value_; }
  friend bool operator!=(const ReverseScalar& x, const ReverseScalar& y) { return x.value_ != y.value_; }

 private:
  ReverseScalar(double value, std::int32_t index) : value_(value), index_(index) {}

  double value_ = 0.0;
  std::int32_t index_ = kConstant;
};

// The functions the EKF and Eigen call, found by argument-dependent lookup.
inline ReverseScalar sqrt(const ReverseScalar& x) {
  const double r = std::sqrt(x.value());
  return ReverseScalar::unary(r, x, 0.5 / r);
}
inline ReverseScalar sin(const ReverseScalar& x) {
  return ReverseScalar::unary(std::sin(x.value()), x, std::cos(x.value()));
}
inline ReverseScalar cos(const ReverseScalar& x) {
  return ReverseScalar::unary(std::cos(x.value()), x, -std::sin(x.value()));
}
inline ReverseScalar exp(const ReverseScalar& x) {
  const double e = std::exp(x.value());
  return ReverseScalar::unary(e, x, e);
}
inline ReverseScalar log(const ReverseScalar& x) {
  return ReverseScalar::unary(std::log(x.value()), x, 1.0 / x.value());
}
inline ReverseScalar abs(const ReverseScalar& x) {
  return ReverseScalar::unary(std::abs(x.value()), x, x.value() < 0.0 ? -1.0 : 1.0);
}
inline ReverseScalar fabs(const ReverseScalar& x) { return abs(x); }
inline ReverseScalar atan2(const ReverseScalar& y, const ReverseScalar& x) {
  const double r2 = x.value() * x.value() + y.value() * y.value();
  return ReverseScalar::binary(std::atan2(y.value(), x.value()), y, x.value() / r2, x, -y.value() / r2);
}
inline ReverseScalar acos(const ReverseScalar& x) {
  return ReverseScalar::unary(std::acos(x.value()), x, -1.0 / std::sqrt(1.0 - x.value() * x.value()));
}
inline ReverseScalar pow(const ReverseScalar& x, double p) {
  return ReverseScalar::unary(std::pow(x.value(), p), x, p * std::pow(x.value(), p - 1.0));
}
inline ReverseScalar abs2(const ReverseScalar& x) { return x * x; }
inline ReverseScalar conj(const ReverseScalar& x) { return x; }
inline ReverseScalar real(const ReverseScalar& x) { return x; }
inline ReverseScalar imag(const ReverseScalar&) { return ReverseScalar(0.0); }
inline bool isfinite(const ReverseScalar& x) { return std::isfinite(x.value()); }
inline bool isnan(const ReverseScalar& x) { return std::isnan(x.value()); }
inline bool isinf(const ReverseScalar& x) { return std::isinf(x.value()); }
inline ReverseScalar max(const ReverseScalar& x, const ReverseScalar& y) { return x < y ? y : x; }
inline ReverseScalar min(const ReverseScalar& x, const ReverseScalar& y) { return y < x ? y : x; }

// For reporting (ml_ekf.hpp's scalarPart for doubles and Jets).
inline double scalarPart(const ReverseScalar& x) { return x.value(); }

}  // namespace headingd::calib

namespace Eigen {

template <>
struct NumTraits<headingd::calib::ReverseScalar> : GenericNumTraits<headingd::calib::ReverseScalar> {
  using Real = headingd::calib::ReverseScalar;
  using NonInteger = headingd::calib::ReverseScalar;
  using Nested = headingd::calib::ReverseScalar;
  using Literal = headingd::calib::ReverseScalar;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 1,
    AddCost = 2,
    MulCost = 3,
  };
  static Real epsilon() { return Real(std::numeric_limits<double>::epsilon()); }
  static Real dummy_precision() { return Real(1e-12); }
  static Real highest() { return Real(std::numeric_limits<double>::max()); }
  static Real lowest() { return Real(std::numeric_limits<double>::lowest()); }
  static Real infinity() { return Real(std::numeric_limits<double>::infinity()); }
  static Real quiet_NaN() { return Real(std::numeric_limits<double>::quiet_NaN()); }
  static int digits10() { return std::numeric_limits<double>::digits10; }
};

}  // namespace Eigen
