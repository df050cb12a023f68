// FFTW transforms of fixed length, planned once and reused for every segment.
#pragma once

#include <fftw3.h>

#include <cmath>
#include <complex>
#include <memory>

namespace cdpost {

struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};
struct PlanDestroy {
  void operator()(fftw_plan_s* plan) const { fftw_destroy_plan(plan); }
};

// Real-to-complex: X_k = sum_n x_n exp(-2 pi i k n / N), k = 0 .. N/2.
class RealTransform {
 public:
  explicit RealTransform(size_t n)
      : n_(n),
        input_(fftw_alloc_real(n)),
        output_(fftw_alloc_complex(n / 2 + 1)),
        plan_(fftw_plan_dft_r2c_1d(static_cast<int>(n), input_.get(), output_.get(), FFTW_ESTIMATE))
  {
  }
  double* input() { return input_.get(); }
  void execute() { fftw_execute(plan_.get()); }
  std::complex<double> value(size_t k) const { return {output_.get()[k][0], output_.get()[k][1]}; }
  double magnitude(size_t k) const { return std::abs(value(k)); }
  size_t bins() const { return n_ / 2 + 1; }

 private:
  size_t n_;
  std::unique_ptr<double, FftwFree> input_;
  std::unique_ptr<fftw_complex, FftwFree> output_;
  std::unique_ptr<fftw_plan_s, PlanDestroy> plan_;
};

}  // namespace cdpost
