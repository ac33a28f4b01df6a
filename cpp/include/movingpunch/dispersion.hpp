// Critical speed of the layer on springs: the minimum phase speed of free waves.
#pragma once

namespace movingpunch {

// Lowest vstar in (0, rayleigh) at which a free wave of wavenumber t = alpha h
// exists; rayleigh_vstar(nu) when there is none below it. kp: the Pasternak
// shear layer (the base's stiffness kw + kp t^2; 0: Winkler).
double first_wave_vstar(double t, double kw, double nu, double kp = 0.0);
// The same with `scan` points in the search for the first sign change (the
// default, kFirstWaveScan, gives the same speeds as 96 and 192 points on
// 61 000 (t, kw, nu) samples: the lowest root is far from the next).
inline constexpr int kFirstWaveScan = 32;
double first_wave_vstar(double t, double kw, double nu, double kp, int scan);
// An integer fourth argument would silently become kp: write
// first_wave_vstar(t, kw, nu, kp, scan) (or kp as a double).
double first_wave_vstar(double t, double kw, double nu, int) = delete;

struct CriticalSpeed {
  double vstar = 0;  // V*_cr = rho V_cr^2 / mu
  double t = 0;      // alpha h at the minimum (inf for a rigid base)
};

// V*_cr(kw, nu, kp) = min over t of first_wave_vstar (the Rayleigh value when
// kw = inf, or when no free wave is slower than the Rayleigh wave: then t =
// inf). Cached per (kw, nu, kp); thread-safe. kp in [0, kMaxKp].
CriticalSpeed critical_speed(double kw, double nu, double kp = 0.0);
inline double critical_vstar(double kw, double nu, double kp = 0.0) {
  return critical_speed(kw, nu, kp).vstar;
}

}  // namespace movingpunch
