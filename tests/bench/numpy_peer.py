#!/usr/bin/env python3
"""NumPy peer of bench_reference's chain (tests/bench/reference_bench.cc), for a side-by-side
timing: the same shapes and the same algorithms, written as vectorised NumPy.

Workload (as BM_ReferenceBlock/channels:12/samples:16000/tracking:0/drift:0): 12 channels x 12
paths, an 8001-bin decoupled FRF set (0..4000 Hz every 0.5 Hz, three random housing modes per
channel-path pair plus a direct term), the Table-1 train at 600 r/min (mesh tones 280 and 238 Hz,
7 Hz modulation, 5 % noise), 8 kHz, 16 000 samples per channel (float32), MWI K = 50 with the
noise-floor rule (eta = 1e-3), kurtogram depth 6 capped by the 120 Hz minimum band width. The
numbers come from NumPy's generator, not from std::mt19937_64: same distributions and sizes,
not the same bits.

Stages, each timed with time.perf_counter (median over --reps blocks after --warmup blocks; the
whole block and the precompute also in process CPU time, which a loaded machine inflates less):
  spectra         float32 -> float64, one-sided amplitude spectra of the 12 channels (rfft)
  identification  F_k = G_k x_k for every bin: one batched (8001, 12, 12) @ (8001, 12, 1) matmul
                  (G_k = D V diag(phi/sigma) U^H precomputed, as core/inverse does for the
                  noise-floor rule)
  residual/contrib per-bin residual ||x - H F|| and its band figure, path energies and the
                  sideband criterion (sum_c |H_cp|^2 |F_p|^2), dominant path, its contribution
                  at every channel back in time (12 inverse FFTs), raw and reconstructed signals
  kurtogram       AR(64) whitening (Levinson-Durbin), Tukey taper, frequency-domain 1/3-binary
                  filter bank, spectral kurtosis of every band (one batched IFFT per row), for the
                  raw and the reconstructed signal
  envelope        band-pass on the chosen band, squared envelope spectrum, five shaft harmonics
                  of each of the three shafts, for both signals
  transient gate  per measured channel: each shaft's revolution median (cubic resampling, median
                  over the revolutions) read back and subtracted in turn, the residual whitened
                  (rfft, unit magnitudes, irfft), 2-ms windows over 12 x the median window
                  marked, the broadband part (lines clipped to 3 x their 32-bin median) taken out
                  on the marks (core/dsp/transient_gate.h); the indicators then read the cleaned
                  channels
  indicators      time-synchronous average of 36 signals (12 measured, 12 path contributions at
                  their best channel, 12 forces) at each of the 2 shaft rates (cubic Lagrange
                  resampling), order spectra, regular / residual / difference signals and the 14
                  condition indicators, per-mesh sideband energies, exclusive residual
  scoring         robust z of every indicator against the healthy baseline and the block score
Precompute (as BM_ReferencePrecompute, Create + Prepare): FRF onto the block grid, MWI weights
(Eq. 40), singular values of H (condition), SVD of H W^{1/2}, filter factors and G_k, |H|^2
tables, masks, kurtogram band tables. Generating the synthetic FRF set is outside both timings.

Not mirrored (cheap or not exercised at constant speed): localisation tracking (the C++ machine
decides on its first block not to track a constant-speed block), transfer signatures, the
verdict's localisation and the alarm model; the reconstructed signal is taken from the dominant
path's signals instead of being transformed a second time (one 16 000-point inverse FFT).

usage:
  numpy_peer.py [--reps N] [--warmup N] [--precompute-reps N] [--json FILE]
  numpy_peer.py --check      # correctness checks (ctest numpy_peer_check)
"""
import argparse
import json
import os
import sys
import time

# One thread, like the C++ benchmark (which runs its chain on one core).
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402

FS = 8000.0
SPEED_HZ = 10.0
ETA = 1e-3              # noise-floor rule: phi = 1/2 at sigma = ETA * sigma_1
ITERATIONS = 50         # MWI K
KURTOGRAM_DEPTH = 6
AR_ORDER = 64
TAPER_FRACTION = 0.1
SIGNIFICANCE_SIGMAS = 5.0
MIN_BINS_PER_BAND = 8
HARMONICS = 5
HARMONIC_TOLERANCE = 0.02
SIDEBAND_ORDERS = 6     # dominant-path criterion: h fm +/- k fs, k = 1..6
LOW_SHAFT_ORDERS = 2    # condition indicators: shaft orders 1..L are "regular"
CI_SIDEBANDS = 3        # condition indicators: per-mesh sidebands h z +/- k, k = 1..3
COMMON_ORDER_TOLERANCE = 0.1
SCALE_FLOOR = 0.05
LIMIT_Z = 5.0

# Table-1 train: shafts input / intermediate / output; gears (name, teeth, shaft); meshes.
SHAFT_RATIO = np.array([1.0, 28.0 / 40.0, 28.0 / 40.0 * 34.0 / 34.0])
GEARS = [("G1", 28, 0), ("G2", 40, 1), ("G3", 34, 1), ("G4", 34, 2)]
MESHES = [(0, 1), (2, 3)]
CI_NAMES = ["fm0", "fm4", "na4", "m6a", "m8a", "energy_ratio", "sideband_level_factor",
            "mesh_harmonics", "residual_rms", "residual_low_orders", "residual_high_orders",
            "tsa_rms", "crest_factor", "synchronous_low_orders"]
TWO_SIDED = (CI_NAMES.index("mesh_harmonics"), CI_NAMES.index("tsa_rms"))


# ----------------------------------------------------------------------------------------------
# Synthetic inputs (outside every timing).

def reference_frf(channels, paths, bins, f_hi, seed=42):
    """(bins, channels, paths) complex FRFs at linspace(0, f_hi, bins): per pair three modes of
    random frequency (300..3500 Hz), damping (1..4 %) and gain, plus 1e-3 on the own path."""
    rng = np.random.default_rng(seed)
    freq = np.linspace(0.0, f_hi, bins)
    fn = rng.uniform(300.0, 3500.0, (channels, paths, 3))
    zeta = rng.uniform(0.01, 0.04, (channels, paths, 3))
    gain = rng.uniform(-1.0, 1.0, (channels, paths, 3))
    w = 2.0 * np.pi * freq[:, None, None]
    own = (np.arange(channels)[:, None] % paths) == np.arange(paths)[None, :]
    h = np.broadcast_to(np.where(own, 1e-3, 0.0), (bins, channels, paths)).astype(complex)
    for i in range(3):
        wn = 2.0 * np.pi * fn[:, :, i]
        h = h + 1e-3 * gain[:, :, i] * w * w / ((wn * wn - w * w) + 2j * zeta[:, :, i] * wn * w)
    return freq, h


def reference_block(channels, n, fs=FS, seed=7):
    """channels x n float32: mesh 1 (280 Hz, 20 % at 7 Hz) + mesh 2 (238 Hz) + 5 % noise."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / fs
    c = np.arange(channels)[:, None].astype(float)
    v = ((1.0 + 0.2 * np.cos(2 * np.pi * 7.0 * t)) * np.cos(2 * np.pi * 280.0 * t + 0.3 * c)
         + 0.6 * np.cos(2 * np.pi * 238.0 * t + 0.7 * c))
    return (v + rng.normal(0.0, 0.05, (channels, n))).astype(np.float32)


# ----------------------------------------------------------------------------------------------
# MWI (core/inverse/mwi.h, spectral_filter.h): F = D V diag(phi / sigma) U^H x, B = H D = U S V^H,
# D = W^{1/2}, W = diag(1 / ||row_i(H^H H)||), phi = 1 - (alpha / (sigma^2 + alpha))^K.

def mwi_weights(h):
    """Eq. 40, batched over the leading axis; weight 0 for a zero column (unobservable path)."""
    a = np.matmul(np.conj(np.swapaxes(h, -1, -2)), h)
    norm = np.sqrt(np.sum(a.real ** 2 + a.imag ** 2, axis=-1))
    with np.errstate(divide="ignore"):
        return np.where(norm > 0.0, 1.0 / norm, 0.0)


def mwi_filter(sigma, alpha, iterations):
    """phi(sigma) = -expm1(K log1p(-s^2 / (s^2 + alpha))), 0 where sigma = 0."""
    s2 = sigma * sigma
    with np.errstate(divide="ignore", invalid="ignore"):
        phi = -np.expm1(iterations * np.log1p(-s2 / (s2 + alpha)))
    return np.where(sigma > 0.0, phi, 0.0)


def noise_floor_alpha(sigma_max, eta, iterations):
    """alpha such that phi = 1/2 at sigma = eta * sigma_max (ParameterForCutoff)."""
    return (eta * sigma_max) ** 2 / np.expm1(np.log(2.0) / iterations)


def mwi_operator(h, iterations, eta=None, alpha=None):
    """Per-bin G = D V diag(phi / sigma) U^H for a stack of H (..., m, n). Either eta (noise
    floor, per bin) or a fixed alpha. Returns G, alpha per bin, sigma of B, condition of H."""
    w = mwi_weights(h)
    d = np.sqrt(w)
    sigma_h = np.linalg.svd(h, compute_uv=False)
    u, s, vh = np.linalg.svd(h * d[..., None, :], full_matrices=False)
    if alpha is None:
        alpha = noise_floor_alpha(s[..., 0], eta, iterations)
    alpha = np.broadcast_to(np.asarray(alpha, float), s.shape[:-1])
    phi = mwi_filter(s, alpha[..., None], iterations)
    with np.errstate(divide="ignore", invalid="ignore"):
        g = np.where(phi > 0.0, phi / s, 0.0)
    # D V diag(g) U^H
    left = d[..., :, None] * np.conj(np.swapaxes(vh, -1, -2)) * g[..., None, :]
    op = np.matmul(left, np.conj(np.swapaxes(u, -1, -2)))
    with np.errstate(divide="ignore"):
        cond_h = np.where(sigma_h[..., -1] > 0.0, sigma_h[..., 0] / sigma_h[..., -1], np.inf)
    return op, alpha, s, cond_h


def mwi_by_iteration(h, x, alpha, iterations):
    """The literal iteration (A W + alpha I) f_{k+1} = H^H x + alpha f_k from f_0 = 0, F = W f_K
    (reference for --check only; batched over the leading axis)."""
    w = mwi_weights(h)
    hh = np.conj(np.swapaxes(h, -1, -2))
    a = np.matmul(hh, h)
    n = h.shape[-1]
    alpha = np.asarray(alpha, float).reshape(-1, 1, 1)
    m = a * w[:, None, :] + alpha * np.eye(n)
    y = np.matmul(hh, x[..., None])
    f = np.zeros_like(y)
    for _ in range(iterations):
        f = np.linalg.solve(m, y + alpha * f)
    return w * f[..., 0]


# ----------------------------------------------------------------------------------------------
# DSP helpers.

def amplitude_spectrum(x):
    """One-sided amplitude spectrum along the last axis (core/dsp/spectrum.h scaling)."""
    n = x.shape[-1]
    s = np.fft.rfft(x, axis=-1)
    s *= 2.0 / n
    s[..., 0] = s[..., 0].real * 0.5
    if n % 2 == 0:
        s[..., -1] = s[..., -1].real * 0.5
    return s


def inverse_amplitude(s, n):
    """Real block(s) of length n from their amplitude spectra."""
    x = s * (n / 2.0)
    x[..., 0] = s[..., 0].real * n
    if n % 2 == 0:
        x[..., -1] = s[..., -1].real * n
    return np.fft.irfft(x, n=n, axis=-1)


def mark_lines(mask, freqs, bin_hz, tolerance_bins, value):
    """mask[k] = value for bins within +/- tolerance_bins of each frequency."""
    if freqs.size == 0:
        return
    centre = freqs / bin_hz
    lo = np.maximum(np.ceil(centre - tolerance_bins), 0).astype(int)
    hi = np.minimum(np.floor(centre + tolerance_bins), mask.size - 1).astype(int)
    span = int(np.max(hi - lo)) + 1 if lo.size else 0
    for j in range(max(span, 0)):
        k = lo + j
        ok = k <= hi
        mask[k[ok]] = value


def sideband_mask(bins, bin_hz, meshes, orders, lo_hz, hi_hz):
    """Bins at h fm +/- k fs (k = 1..orders) inside [lo, hi], mesh harmonics excluded."""
    mask = np.zeros(bins, dtype=bool)
    top = bin_hz * (bins - 1)
    k = np.arange(1, orders + 1)
    for fm, shafts in meshes:
        hmax = int(np.floor((top + orders * max(shafts)) / fm))
        h = np.arange(1, hmax + 1)[:, None, None, None]
        sign = np.array([-1.0, 1.0])[None, :, None, None]
        rates = np.asarray(shafts)[None, None, None, :]
        f = (h * fm + sign * k[None, None, :, None] * rates).ravel()
        f = f[(f >= lo_hz) & (f <= hi_hz) & (f > 0.0)]
        mark_lines(mask, f, bin_hz, 1.0, True)
    for fm, _ in meshes:
        h = np.arange(1, int(np.floor((top + bin_hz) / fm)) + 1)
        mark_lines(mask, h * fm, bin_hz, 1.0, False)
    return mask


class KurtogramPlan:
    """Fast kurtogram (core/dsp/kurtogram.h): 1/3-binary tree of rows 0, 1, 1.6, ..., depth, each
    band's bins of the tapered block moved to baseband and inverse transformed with zero padding
    to >= twice its width; SK = <|c|^4>/<|c|^2>^2 / r - 2 (r corrects for the Tukey taper)."""

    def __init__(self, n, fs, depth, min_bandwidth_hz):
        self.n, self.fs = n, fs
        positive = n // 2
        candidates = [(0, False)]
        for level in range(1, depth + 1):
            candidates.append((level, False))
            if level < depth:
                candidates.append((level, True))
        self.rows = []
        for level, ternary in candidates:
            bands = 3 << (level - 1) if ternary else 1 << level
            first = self.first_bins(bands)
            widths = np.diff(first)
            if fs / (2.0 * bands) < min_bandwidth_hz or widths.min() < MIN_BINS_PER_BAND:
                break
            size = 1 << int(np.ceil(np.log2(2 * widths.max())))
            # Gather index into [spectrum, 0]: band i's bins first, the sentinel zero after.
            j = np.arange(size)[None, :]
            idx = np.where(j < widths[:, None], first[:-1, None] + j, positive + 1)
            self.rows.append(dict(level=level, ternary=ternary, bands=bands, size=size, idx=idx,
                                  first=first))
        taper = np.ones(n)
        m = int(TAPER_FRACTION * n / 2.0)
        if m > 0:
            w = 0.5 * (1.0 - np.cos(np.pi * (np.arange(m) + 0.5) / m))
            taper[:m] = w
            taper[n - m:] = w[::-1]
        self.taper = taper
        self.taper_ratio = np.mean(taper ** 4) / np.mean(taper ** 2) ** 2

    def first_bins(self, bands):
        """First bin of each band and one past the last: max(ceil(i N / 2L), 1), N/2 + 1."""
        i = np.arange(bands + 1)
        k = np.maximum((i * self.n + 2 * bands - 1) // (2 * bands), 1)
        k[-1] = self.n // 2 + 1
        return k

    def process(self, block):
        x = block - block.mean()
        x = whiten(x, AR_ORDER)
        spec = np.fft.rfft(x * self.taper)
        spec[0] = 0.0
        ext = np.append(spec, 0.0)
        best = (-np.inf, None, 0)
        for row in self.rows:
            c = np.fft.ifft(ext[row["idx"]], axis=1)
            p = c.real ** 2 + c.imag ** 2
            m2 = p.sum(axis=1)
            m4 = (p * p).sum(axis=1)
            size = float(row["size"])
            with np.errstate(divide="ignore", invalid="ignore"):
                sk = np.where(m2 > 0.0, (m4 / size) / (m2 / size) ** 2 / self.taper_ratio - 2.0,
                              0.0)
            i = int(np.argmax(sk))
            if sk[i] > best[0]:
                best = (float(sk[i]), row, i)
        sk, row, i = best
        bw = self.fs / (2.0 * row["bands"])
        bins = row["first"][i + 1] - row["first"][i]
        sigma = 2.0 / np.sqrt(bins)
        return dict(low_hz=i * bw, high_hz=(i + 1) * bw, kurtosis=sk, sigma=sigma,
                    level=row["level"], ternary=row["ternary"], index=i,
                    significant=sk > SIGNIFICANCE_SIGMAS * sigma)


def whiten(x, order):
    """AR prediction error (biased autocorrelation, Levinson-Durbin); first `order` samples 0."""
    n = x.size
    # Direct lags and direct filtering: at order 64 they beat the 32768-point transforms that
    # an FFT route needs (measured with NumPy 1.24's pocketfft).
    r = np.array([np.dot(x[lag:], x[:n - lag]) for lag in range(order + 1)]) / n
    if not r[0] > 0.0:
        return x
    a = np.zeros(order + 1)
    a[0] = 1.0
    error = r[0] * (1.0 + 1e-9)  # the C++'s diagonal load
    for i in range(1, order + 1):
        acc = r[i] + np.dot(a[1:i], r[i - 1:0:-1])
        k = -acc / error
        a[1:i] = a[1:i] + k * a[i - 1:0:-1]
        a[i] = k
        error *= 1.0 - k * k
        if not error > 0.0:
            break
    e = np.convolve(x, a)[:n]  # e[i] = sum_j a[j] x[i - j]
    e[:order] = 0.0
    return e


def band_pass(x, lo_hz, hi_hz, fs, transition_hz):
    """Zero-phase gain: 1 on [lo, hi], raised-cosine roll-off over transition_hz outside."""
    n = x.size
    f = np.arange(n // 2 + 1) * (fs / n)
    dist = np.where(f < lo_hz, lo_hz - f, np.where(f > hi_hz, f - hi_hz, 0.0))
    gain = np.where(dist <= 0.0, 1.0,
                    np.where(dist >= transition_hz, 0.0,
                             0.5 * (1.0 + np.cos(np.pi * dist / max(transition_hz, 1e-300)))))
    return np.fft.irfft(np.fft.rfft(x) * gain, n=n)


def squared_envelope_spectrum(x):
    """|S{e^2 - <e^2>}| / <e^2>, e^2 = |analytic signal|^2 (core/dsp/envelope_spectrum.h)."""
    n = x.size
    spec = np.fft.rfft(x)
    z = np.zeros(n, dtype=complex)
    half = n // 2
    z[0] = spec[0]
    z[1:(n + 1) // 2] = 2.0 * spec[1:(n + 1) // 2]
    if n % 2 == 0:
        z[half] = spec[half]
    e = np.fft.ifft(z)
    e2 = e.real ** 2 + e.imag ** 2
    mean = e2.mean()
    if not mean > 0.0:
        return np.zeros(half + 1)
    ses = np.abs(amplitude_spectrum(e2 - mean)) / mean
    ses[0] = 0.0
    return ses


def harmonic_indicator(ses, bin_hz, fc):
    """Sum over h = 1..5 of the largest SES value within +/- max(bin, tol h fc) of h fc."""
    last = ses.size - 1
    amps = np.empty(HARMONICS)
    for h in range(1, HARMONICS + 1):
        target = h * fc
        hw = max(bin_hz, HARMONIC_TOLERANCE * target)
        lo = int(min(max(np.ceil((target - hw) / bin_hz - 1e-9), 0), last))
        hi = int(min(max(np.floor((target + hw) / bin_hz + 1e-9), 0), last))
        amps[h - 1] = ses[lo:hi + 1].max()
    return amps.sum(), amps


# ----------------------------------------------------------------------------------------------
# Synchronous average and condition indicators (core/dsp/synchronous_average.h,
# core/diagnosis/gear_condition_indicators.h), batched over signals.

def cubic_stencils(u, length):
    """The cubic stencil at each position u >= 0 of a signal of `length` samples
    (cubic_interpolation.h's MakeCubicStencil): its first sample and its four Lagrange weights
    (len(u), 4)."""
    i = u.astype(np.int64)
    first = np.minimum(np.where(i == 0, 0, i - 1), length - 4)
    t = u - first
    a, b, c = t - 1.0, t - 2.0, t - 3.0
    return first, np.stack([-a * b * c / 6.0, t * b * c / 2.0, -t * a * c / 2.0,
                            t * a * b / 6.0], axis=1)


def tsa_plan(n, fs, shaft_hz, max_points):
    spr = fs / shaft_hz
    whole = int(np.floor((n - 1) / spr))
    m = max_points if spr >= max_points else max(4, 1 << int(np.ceil(np.log2(np.ceil(spr)))))
    # Four Lagrange weights per point (RM, 4) and the samples they read, flattened (4 RM).
    first, w = cubic_stencils(np.arange(whole * m) * (spr / m), n)
    taps = (first[:, None] + np.arange(4)).ravel()
    return dict(m=m, revolutions=whole, taps=taps, w=w, nyquist_order=0.5 * spr)


def tsa(samples, plan, spread_signals=0):
    """TSA (S, M) and order spectra (S, M/2 + 1) of S signals given as samples (n, S): each
    resampled point gathers four rows of S values, so all signals share one gather. With
    spread_signals = s, also the first s signals' locked power and spread between revolutions
    per order (s, M/2 + 1) each, from Hann-windowed revolutions (synchronous_average.h)."""
    m, r = plan["m"], plan["revolutions"]
    s = samples.shape[1]
    points = np.einsum("pjs,pj->ps", samples[plan["taps"]].reshape(-1, 4, s), plan["w"])
    revs = points.reshape(r, m, s)
    avg = revs.mean(axis=0).T
    orders = amplitude_spectrum(avg)
    half = m // 2
    if plan["nyquist_order"] < half:
        orders[:, int(np.floor(plan["nyquist_order"])) + 1:] = 0.0
        avg = inverse_amplitude(orders, m)
    if not spread_signals:
        return avg, orders, None
    hann = 0.5 - 0.5 * np.cos(2 * np.pi * np.arange(m) / m)
    y = np.fft.rfft(revs[:, :, :spread_signals] * hann[None, :, None], axis=1) * (4.0 / m)
    y[:, 0] *= 0.5
    y[:, half] *= 0.5
    mean = y.mean(axis=0)
    locked = np.abs(mean) ** 2
    spread = np.maximum(0.0, (np.abs(y) ** 2).mean(axis=0) - locked)
    return avg, orders, (locked.T, spread.T, r, plan["nyquist_order"])


# ----------------------------------------------------------------------------------------------
# Transient gate (core/dsp/transient_gate.h, ConditionIndicatorStage::RemoveTransients), batched
# over the measured channels: each rate group's revolution median taken out in turn, the
# residual whitened, windows far above the median window marked, and the residual's broadband
# part (lines clipped to 3 x their 32-bin median) on the marks taken out of the channel.

GATE_WINDOW_SECONDS = 2e-3
GATE_EDGE_WINDOWS = 8
GATE_MARK_RATIO = 12.0
GATE_BEFORE, GATE_AFTER = 1, 4
GATE_LINE_BINS = 32
GATE_LINE_RATIO = 3.0
GATE_TAIL_RATIO = 0.5


def ramp(d, length):
    return 0.5 - 0.5 * np.cos(np.pi * (np.asarray(d, float) + 0.5) / length)


def periodic_read(plan, n, shaft_hz, fs):
    """Each sample's four taps into a revolution of M points wrapped as [last, 0..M-1, 0, 1] and
    their cubic Lagrange weights (n, 4) each (PlanPeriodicRead)."""
    m = plan["m"]
    x = np.arange(n) * (shaft_hz / fs * m)
    first, w = cubic_stencils(x - m * np.floor(x / m) + 1.0, m + 3)
    return first[:, None] + np.arange(4), w


def gate_peaks(whitened, w, edge):
    """Marked windows (windows, S): those over 12 x the median window of the whitened residual
    and their neighbours, none within the end ramps (MarkPeaks())."""
    n, s = whitened.shape
    windows = n // w
    e = (whitened[:windows * w] ** 2).reshape(windows, w, s).sum(axis=1)
    median = np.partition(e, windows // 2, axis=0)[windows // 2]
    over = (e > GATE_MARK_RATIO * median) & (median > 0.0)
    marked = np.zeros((windows, s), bool)
    for shift in range(-GATE_AFTER, GATE_BEFORE + 1):  # window k marks k - 1 .. k + 4
        src = over[max(0, shift):windows + min(0, shift)]
        marked[max(0, -shift):windows - max(0, shift)] |= src
    edge_windows = edge // w
    marked[:edge_windows] = False
    marked[windows - edge_windows:] = False
    return marked


def gate_tails(marked, broadband, w):
    """Marked samples (n, S): each stretch of marked windows (windows, S) extended through the
    windows whose broadband energy stays over the tail level (ExtendThroughTails())."""
    windows, s = marked.shape
    n = broadband.shape[0]
    eb = (broadband[:windows * w] ** 2).reshape(windows, w, s).sum(axis=1)
    ok = eb > GATE_TAIL_RATIO * np.partition(eb, windows // 2, axis=0)[windows // 2]
    k = np.arange(windows)[:, None]
    last_mark = np.maximum.accumulate(np.where(marked, k, -1), axis=0)
    last_break = np.maximum.accumulate(np.where(ok, -1, k), axis=0)
    marked = marked | ((last_mark >= 0) & (last_break <= last_mark))
    mask = np.zeros((n, s), bool)
    mask[:windows * w] = np.repeat(marked, w, axis=0)
    return mask


def subtract_shafts(x, plans, shaft_hz, fs):
    """x (n, S) less each shaft's revolution median, read back at every sample, in turn (so a
    line two shafts share is taken once)."""
    n, s = x.shape
    residual = x.copy()
    for plan, f in zip(plans, shaft_hz):
        m, r = plan["m"], plan["revolutions"]
        points = np.einsum("pjs,pj->ps", residual[plan["taps"]].reshape(-1, 4, s), plan["w"])
        median = np.median(points.reshape(r, m, s), axis=0)                  # (M, S)
        wrapped = np.concatenate([median[-1:], median, median[:2]], axis=0)   # (M + 3, S)
        taps, weights = periodic_read(plan, n, f, fs)
        residual -= np.einsum("pjs,pj->ps", wrapped[taps], weights)
    return residual


def transient_gate(x, plans, shaft_hz, fs):
    """x (n, S) measured channels; plans/shaft_hz per rate group. Returns the cleaned channels
    (n, S) and the marked samples per channel."""
    transient, marked = gate_estimate(subtract_shafts(x, plans, shaft_hz, fs), fs)
    return x - transient, marked


def gate_estimate(residual, fs):
    """The transients of residual (n, S) (TransientGate::Estimate) and the marked samples."""
    n, s = residual.shape
    w = int(np.clip(round(GATE_WINDOW_SECONDS * fs), 4, n // 16))
    edge = min(n // 4, GATE_EDGE_WINDOWS * w)
    edges = ramp(np.arange(edge), edge)
    tapered = residual.copy()
    tapered[:edge] *= edges[:, None]
    tapered[n - edge:] *= edges[::-1, None]
    spec = np.fft.rfft(tapered, axis=0)
    mag = np.abs(spec)
    white = np.divide(spec, mag, out=np.zeros_like(spec), where=mag > 0.0)
    white[0] = 0.0
    whitened = np.fft.irfft(white, n=n, axis=0)
    peaks = gate_peaks(whitened, w, edge)
    transient = np.zeros_like(residual)
    marked = np.zeros(s, np.int64)
    hit = np.flatnonzero(peaks.any(axis=0))  # only these channels need their broadband part
    if hit.size == 0:
        return transient, marked
    spec, mag, peaks = spec[:, hit], mag[:, hit], peaks[:, hit]
    bins = spec.shape[0]
    blocks = bins // GATE_LINE_BINS
    level = np.partition(mag[:blocks * GATE_LINE_BINS].reshape(blocks, GATE_LINE_BINS, hit.size),
                         GATE_LINE_BINS // 2, axis=1)[:, GATE_LINE_BINS // 2]  # (blocks, hit)
    at = np.clip((np.arange(bins) - 0.5 * GATE_LINE_BINS) / GATE_LINE_BINS, 0.0, blocks - 1)
    b0 = at.astype(np.int64)
    b1 = np.minimum(b0 + 1, blocks - 1)
    f = (at - b0)[:, None]
    line = GATE_LINE_RATIO * ((1.0 - f) * level[b0] + f * level[b1])
    gain = np.where(mag > line, line / np.where(mag > 0.0, mag, 1.0), 1.0)
    clipped = spec * gain
    clipped[0] = 0.0
    broadband = np.fft.irfft(clipped, n=n, axis=0)
    mask = gate_tails(peaks, broadband, w)
    # Each stretch ramped over one window at its edges (distance to the nearest unmarked sample).
    i = np.arange(n)[:, None]
    left = i - np.maximum.accumulate(np.where(mask, -1, i), axis=0)
    right = (i - np.maximum.accumulate(np.where(mask[::-1], -1, i), axis=0))[::-1]
    d = np.minimum(np.minimum(left, right) - 1, w)
    transient[:, hit] = np.where(mask, np.where(d >= w, 1.0, ramp(np.maximum(d, 0), w)) * broadband,
                                 0.0)
    marked[hit] = mask.sum(axis=0)
    return transient, marked


class IndicatorLayout:
    """Line roles of one rate group's order spectrum (M points, the group's mesh orders)."""

    def __init__(self, m, mesh_orders, other_ratios, ratio):
        half = m // 2
        k = np.arange(half + 1)
        mesh = np.zeros(half + 1, bool)
        first_sb = np.zeros(half + 1, bool)
        near = np.zeros((len(mesh_orders), half + 1), bool)
        self.mesh_lines = []
        for j, z in enumerate(mesh_orders):
            lines = z * np.arange(1, half // z + 1)
            self.mesh_lines.append(lines)
            mesh[lines] = True
            first_sb[lines - 1] = True
            first_sb[lines[lines + 1 <= half] + 1] = True
            for s in range(1, CI_SIDEBANDS + 1):
                near[j, lines[lines > s] - s] = True
                near[j, lines[lines + s <= half] + s] = True
        shaft = (k >= 1) & (k <= min(half, LOW_SHAFT_ORDERS))
        regular = mesh | shaft
        interior = k >= 1
        single = near.sum(axis=0) == 1
        self.half, self.m = half, m
        self.mesh_orders = np.asarray(mesh_orders)
        self.regular = regular
        self.low = interior & ~regular & (2 * k < min(mesh_orders))
        self.high = interior & ~regular & (k > max(mesh_orders))
        self.sideband = [near[j] & single & ~regular & interior for j in range(len(mesh_orders))]
        keep = np.stack([regular, ~regular, ~regular & ~first_sb])
        keep[:, 0] = False
        self.keep = keep  # regular, residual, difference
        excl = k > LOW_SHAFT_ORDERS
        for z in mesh_orders:
            excl &= (k % z) != 0
        for other in other_ratios:
            x = k * ratio / other
            excl &= np.abs(x - np.round(x)) > COMMON_ORDER_TOLERANCE
        self.exclusive = excl


def central_moments(x):
    mean = x.mean(axis=-1, keepdims=True)
    d2 = (x - mean) ** 2
    d4 = d2 * d2
    return (d2.mean(axis=-1), d4.mean(axis=-1), (d4 * d2).mean(axis=-1), (d4 * d4).mean(axis=-1))


def condition_indicators(avg, orders, lay, na4_reference, spread=None):
    """(S, 14 + meshes + 1) values and the residual variance (S,) of a stack of TSAs; the
    synchronous low-order ratio only for the signals `spread` covers (0 for the rest)."""
    half = lay.half
    energy = 0.5 * (orders.real ** 2 + orders.imag ** 2)
    energy[:, half] = orders[:, half].real ** 2
    amp = np.abs(orders)
    mean = avg.mean(axis=1, keepdims=True)
    m2 = ((avg - mean) ** 2).mean(axis=1)
    rms = np.sqrt(m2)
    hi, lo = avg.max(axis=1), avg.min(axis=1)
    mean = mean[:, 0]
    mesh_sum = sum(amp[:, lines].sum(axis=1) for lines in lay.mesh_lines)
    low = energy[:, lay.low].sum(axis=1)
    high = energy[:, lay.high].sum(axis=1)
    sideband = np.stack([energy[:, sb].sum(axis=1) for sb in lay.sideband], axis=1)
    dominant = np.argmax(amp[:, lay.mesh_orders], axis=1)
    zd = lay.mesh_orders[dominant]
    rows = np.arange(avg.shape[0])
    slf_num = amp[rows, zd - 1] + amp[rows, zd + 1]
    spectra = 0.5 * orders[None, :, :] * lay.keep[:, None, :]
    spectra[:, :, half] = orders[None, :, half].real * lay.keep[:, None, half]
    rebuilt = np.fft.irfft(spectra, n=lay.m, axis=-1) * lay.m
    r2, _, _, _ = central_moments(rebuilt[0])
    s2, s4, _, _ = central_moments(rebuilt[1])
    d2, d4, d6, d8 = central_moments(rebuilt[2])

    def ratio(a, b):
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(b > 0.0, a / np.where(b > 0.0, b, 1.0), 0.0)

    zero = 1e-24 * m2
    dz = d2 <= zero
    na4_ref = np.where(na4_reference > 0.0, na4_reference, s2)
    v = np.zeros((avg.shape[0], 14 + len(lay.mesh_orders) + 1))
    v[:, 0] = ratio(hi - lo, mesh_sum)
    v[:, 1] = np.where(dz, 0.0, ratio(d4, d2 * d2))
    v[:, 2] = np.where(s2 > zero, ratio(s4, na4_ref * na4_ref), 0.0)
    v[:, 3] = np.where(dz, 0.0, ratio(d6, d2 ** 3))
    v[:, 4] = np.where(dz, 0.0, ratio(d8, d2 ** 4))
    v[:, 5] = np.where(dz, 0.0, ratio(np.sqrt(d2), np.sqrt(r2)))
    v[:, 6] = ratio(slf_num, rms)
    v[:, 7] = mesh_sum
    v[:, 8] = ratio(np.sqrt(s2), rms)
    v[:, 9] = ratio(low, m2)
    v[:, 10] = ratio(high, m2)
    v[:, 11] = rms
    v[:, 12] = ratio(np.maximum(hi - mean, mean - lo), rms)
    if spread is not None:
        locked, between, r, nyquist = spread
        band = lay.low & (np.arange(lay.half + 1) <= np.floor(nyquist))
        v[:locked.shape[0], 13] = ratio(locked[:, band].sum(axis=1),
                                        between[:, band].sum(axis=1) / (r - 1))
    v[:, 14:14 + sideband.shape[1]] = sideband
    v[:, -1] = energy[:, lay.exclusive[:half + 1]].sum(axis=1)
    return v, s2


# ----------------------------------------------------------------------------------------------
# The chain.

class Chain:
    """One machine: configure() is the precompute, process() one block, stage by stage."""

    def __init__(self, freq, h, n, fs=FS, speed_hz=SPEED_HZ, iterations=ITERATIONS, eta=ETA,
                 depth=KURTOGRAM_DEPTH):
        self.freq, self.h_frf = freq, h
        self.n, self.fs, self.speed_hz = n, fs, speed_hz
        self.iterations, self.eta, self.depth = iterations, eta, depth
        self.channels, self.paths = h.shape[1], h.shape[2]
        self.baseline = None

    # -- precompute
    def configure(self):
        n, fs = self.n, self.fs
        self.bins = n // 2 + 1
        self.bin_hz = fs / n
        fb = np.arange(self.bins) * self.bin_hz
        # FRF onto the block grid (linear interpolation in real and imaginary parts).
        eps = 1e-9 * self.bin_hz
        inside = (fb >= self.freq[0] - eps) & (fb <= self.freq[-1] + eps)
        self.first_bin = int(np.argmax(inside))
        fin = fb[inside]
        j = np.clip(np.searchsorted(self.freq, fin + eps, side="right") - 1, 0, self.freq.size - 1)
        j1 = np.minimum(j + 1, self.freq.size - 1)
        span = np.where(j1 > j, self.freq[j1] - self.freq[j], 1.0)
        t = np.where(np.abs(self.freq[j] - fin) <= eps, 0.0, (fin - self.freq[j]) / span)
        self.h = (1.0 - t)[:, None, None] * self.h_frf[j] + t[:, None, None] * self.h_frf[j1]
        self.in_range = fin.size
        # Identification operator.
        self.g, self.alpha, self.sigma_b, self.cond_h = mwi_operator(self.h, self.iterations,
                                                                     eta=self.eta)
        with np.errstate(divide="ignore"):
            self.cond_w = np.where(self.sigma_b[:, -1] > 0.0,
                                   self.sigma_b[:, 0] / self.sigma_b[:, -1], np.inf)
        cutoff = self.sigma_b[:, :1] * max(self.channels, self.paths) * np.finfo(float).eps
        self.rank = (self.sigma_b > cutoff).sum(axis=1)
        # H and the path-energy table |H_cp|^2 as (paths, channels, bins): one path's FRFs are
        # contiguous rows for the contributions.
        self.hp = np.ascontiguousarray(self.h.transpose(2, 1, 0))
        self.power = self.hp.real ** 2 + self.hp.imag ** 2
        self.band_lo, self.band_hi = max(0.0, self.freq[0]), min(self.freq[-1], fs / 2.0)
        self.band = np.zeros(self.bins, bool)
        self.band[self.first_bin:self.first_bin + self.in_range] = (
            (fin >= self.band_lo) & (fin <= self.band_hi))
        # Train kinematics, rate groups.
        self.max_speed = 1.2 * self.speed_hz
        self.min_bw = 2.0 * HARMONICS * SHAFT_RATIO.max() * self.max_speed
        self.kurtogram = KurtogramPlan(n, fs, self.depth, self.min_bw)
        # Rate groups: shafts at the same rate (within the harmonic tolerance) share one average;
        # each group's distinct meshes and their tooth orders.
        self.groups = []
        group_of = []
        for ratio in SHAFT_RATIO:
            near = [i for i, g in enumerate(self.groups)
                    if abs(g["ratio"] - ratio) <= HARMONIC_TOLERANCE * ratio]
            if not near:
                self.groups.append(dict(ratio=float(ratio), mesh_orders=[], meshes=[]))
            group_of.append(near[-1] if near else len(self.groups) - 1)
        for gi, (_, teeth, shaft) in enumerate(GEARS):
            grp = self.groups[group_of[shaft]]
            mesh = next(mi for mi, pair in enumerate(MESHES) if gi in pair)
            if mesh not in grp["meshes"]:
                grp["meshes"].append(mesh)
                grp["mesh_orders"].append(teeth)
        self.max_points = min(max(1 << int(np.ceil(np.log2(n))), 4), 1 << 16)
        self.layouts = {}
        return self

    def layout(self, g, m):
        key = (g, m)
        if key not in self.layouts:
            grp = self.groups[g]
            others = [o["ratio"] for i, o in enumerate(self.groups) if i != g]
            self.layouts[key] = IndicatorLayout(m, grp["mesh_orders"], others, grp["ratio"])
        return self.layouts[key]

    # -- per block
    def process(self, block, timings=None):
        clock = time.perf_counter
        out = {}
        cpu0 = time.process_time()
        t0 = clock()
        n, bins, first = self.n, self.bins, self.first_bin
        time_sig = block.astype(np.float64)
        spec = amplitude_spectrum(time_sig)
        t1 = clock()

        x = np.ascontiguousarray(spec[:, first:first + self.in_range].T)  # bins x channels
        forces = np.matmul(self.g, x[:, :, None])[:, :, 0]                # bins x paths
        t2 = clock()

        # Residual figures.
        resid = x - np.matmul(self.h, forces[:, :, None])[:, :, 0]
        r2 = (resid.real ** 2 + resid.imag ** 2).sum(axis=1)
        x2 = (x.real ** 2 + x.imag ** 2).sum(axis=1)
        band = self.band[first:first + self.in_range]
        den = x2[band].sum()
        out["relative_residual"] = float(np.sqrt(r2[band].sum() / den)) if den > 0 else 0.0
        finite = np.isfinite(self.alpha) & np.isfinite(self.cond_w)
        out["alpha_median"] = float(np.median(self.alpha[finite]))
        out["condition_median"] = float(np.median(self.cond_w[finite]))
        # Path energies and the sideband criterion.
        speed = self.speed_hz
        meshes = []
        for a, b in MESHES:
            za, sa = GEARS[a][1], GEARS[a][2]
            sb = GEARS[b][2]
            meshes.append((za * SHAFT_RATIO[sa] * speed,
                           (SHAFT_RATIO[sa] * speed, SHAFT_RATIO[sb] * speed)))
        side_mask = sideband_mask(bins, self.bin_hz, meshes, SIDEBAND_ORDERS, self.band_lo,
                                  self.band_hi)[first:first + self.in_range]
        fp = np.ascontiguousarray(forces.T)  # paths x bins (C order: einsum's fast path)
        f2 = np.where(band[None, :], fp.real ** 2 + fp.imag ** 2, 0.0)
        both = np.stack([f2, np.where(side_mask[None, :], f2, 0.0)], axis=1)  # paths x 2 x bins
        per_channel = np.einsum("pck,psk->pcs", self.power, both)             # paths x ch x 2
        energy = per_channel[:, :, 0].sum(axis=1)
        criterion = per_channel[:, :, 1].sum(axis=1)
        best_channel = np.argmax(per_channel[:, :, 0], axis=1)
        positive = np.where(criterion > 0.0, criterion, -np.inf)
        dominant = int(np.argmax(positive)) if np.isfinite(positive).any() else int(
            np.argmax(energy))
        out["dominant_path"] = dominant
        out["shares"] = energy / energy.sum()
        contrib = np.zeros((self.channels, bins), complex)
        contrib[:, first:first + self.in_range] = self.hp[dominant] * fp[dominant]
        dominant_time = inverse_amplitude(contrib, n)
        channel = int(best_channel[dominant])
        out["indicator_channel"] = channel
        raw = inverse_amplitude(spec[channel].copy(), n)
        rec = dominant_time[channel]
        t3 = clock()

        bands = [self.kurtogram.process(raw), self.kurtogram.process(rec)]
        t4 = clock()

        shaft_hz = SHAFT_RATIO * speed
        envelope = []
        for sig, kb in zip((raw, rec), bands):
            lo, hi = (kb["low_hz"], kb["high_hz"]) if kb["significant"] else (
                self.band_lo, min(self.band_hi, self.fs / 2.0))
            filtered = band_pass(sig, lo, hi, self.fs, 0.1 * self.min_bw)
            ses = squared_envelope_spectrum(filtered)
            envelope.append([harmonic_indicator(ses, self.bin_hz, fc)[0] for fc in shaft_hz])
        out["bands"] = bands
        out["envelope"] = np.array(envelope)
        t5 = clock()

        # The measured channels' transients taken out (the C++ condition stage's gate).
        rates = [grp["ratio"] * speed for grp in self.groups]
        plans = [tsa_plan(n, self.fs, f, self.max_points) for f in rates]
        cleaned, _ = transient_gate(np.ascontiguousarray(time_sig.T), plans, rates, self.fs)
        t5g = clock()

        # 36 signals: measured, contributions at each path's best channel, forces.
        cs = np.zeros((2 * self.paths, bins), complex)
        hb = self.hp[np.arange(self.paths), best_channel]                  # paths x bins
        cs[:self.paths, first:first + self.in_range] = hb * fp
        cs[self.paths:, first:first + self.in_range] = fp
        signals = np.concatenate([cleaned.T, inverse_amplitude(cs, n)], axis=0)
        samples = np.ascontiguousarray(signals.T)  # n x 36: one gather serves every signal
        values, variances = [], []
        for g, grp in enumerate(self.groups):
            plan = plans[g]
            avg, orders, spread = tsa(samples, plan, spread_signals=self.channels)
            lay = self.layout(g, plan["m"])
            ref = (self.baseline["residual_variance"][g] if self.baseline is not None
                   else np.zeros(signals.shape[0]))
            v, s2 = condition_indicators(avg, orders, lay, ref,
                                         spread if plan["revolutions"] >= 2 else None)
            values.append(v)
            variances.append(s2)
        out["indicators"] = values
        out["residual_variance"] = variances
        t6 = clock()

        # Scoring against the healthy baseline (log scale, robust z, directional).
        score = 0.0
        if self.baseline is not None:
            scored = self.channels + self.paths  # force signals are not scored
            for g, v in enumerate(values):
                z = (np.log(np.maximum(v[:scored], 1e-300)) - self.baseline["median"][g]) \
                    / self.baseline["scale"][g]
                z[:, TWO_SIDED] = np.abs(z[:, TWO_SIDED])
                score = max(score, float(z.max()) / LIMIT_Z)
            ze = (np.log(np.maximum(out["envelope"], 1e-300)) - self.baseline["envelope"]) \
                / SCALE_FLOOR
            score = max(score, float(ze.max()) / LIMIT_Z)
        out["score"] = score
        t7 = clock()
        cpu7 = time.process_time()

        if timings is not None:
            for name, a, b in (("spectra", t0, t1), ("identification", t1, t2),
                               ("residual/contrib", t2, t3), ("kurtogram", t3, t4),
                               ("envelope", t4, t5), ("transient gate", t5, t5g),
                               ("indicators", t5g, t6),
                               ("scoring", t6, t7)):
                timings.setdefault(name, []).append(b - a)
            timings.setdefault("block", []).append(t7 - t0)
            timings.setdefault("block_cpu", []).append(cpu7 - cpu0)
        return out

    def learn(self, out):
        """A healthy baseline from one block's indicators (median = the block, scale = floor)."""
        scored = self.channels + self.paths
        self.baseline = dict(
            median=[np.log(np.maximum(v[:scored], 1e-300)) for v in out["indicators"]],
            scale=[np.full_like(v[:scored], SCALE_FLOOR) for v in out["indicators"]],
            residual_variance=list(out["residual_variance"]),
            envelope=np.log(np.maximum(out["envelope"], 1e-300)))


STAGES = ["spectra", "identification", "residual/contrib", "kurtogram", "envelope",
          "transient gate", "indicators", "scoring"]


def run_benchmark(args):
    channels, paths, n = 12, 12, 16000
    freq, h = reference_frf(channels, paths, 8001, 4000.0)
    block = reference_block(channels, n)
    pre, pre_cpu = [], []
    chain = None
    for _ in range(args.precompute_reps):
        c = time.process_time()
        t = time.perf_counter()
        chain = Chain(freq, h, n).configure()
        pre.append(time.perf_counter() - t)
        pre_cpu.append(time.process_time() - c)
    out = None
    for i in range(max(args.warmup, 1)):
        out = chain.process(block)
        if i == 0:
            chain.learn(out)
    timings = {}
    for _ in range(args.reps):
        out = chain.process(block, timings)
    ms = {k: 1e3 * float(np.median(v)) for k, v in timings.items()}
    result = dict(
        per_block_ms=ms["block"], stages_ms={k: ms[k] for k in STAGES},
        precompute_ms=1e3 * float(np.median(pre)), reps=args.reps,
        per_block_cpu_ms=ms["block_cpu"], precompute_cpu_ms=1e3 * float(np.median(pre_cpu)),
        precompute_reps=args.precompute_reps, numpy=np.__version__,
        python=sys.version.split()[0], loadavg=list(os.getloadavg()),
        dominant_path=out["dominant_path"], relative_residual=out["relative_residual"],
        alpha_median=out["alpha_median"], raw_band=[out["bands"][0]["low_hz"],
                                                    out["bands"][0]["high_hz"]],
        kurtogram_rows=len(chain.kurtogram.rows))
    print(f"NumPy peer of bench_reference (12 ch x 12 paths, 16000 samples, 8001 bins, "
          f"MWI K = {ITERATIONS}, kurtogram depth {KURTOGRAM_DEPTH} -> "
          f"{len(chain.kurtogram.rows)} rows); NumPy {np.__version__}, Python "
          f"{result['python']}, one BLAS thread")
    print(f"median of {args.reps} blocks after {max(args.warmup, 1)} warm-up; "
          f"load average {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    print(f"  {'stage':<16}{'ms':>10}")
    for k in STAGES:
        print(f"  {k:<16}{ms[k]:>10.2f}")
    print(f"  {'block (total)':<16}{ms['block']:>10.2f}   (CPU {ms['block_cpu']:.2f})")
    print(f"  {'precompute':<16}{result['precompute_ms']:>10.1f}   "
          f"(CPU {result['precompute_cpu_ms']:.1f}; median of {args.precompute_reps})")
    print(f"  dominant path {out['dominant_path']}, relative residual "
          f"{out['relative_residual']:.2e}, median alpha {out['alpha_median']:.3g}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(result, f, indent=1)
    return 0


# ----------------------------------------------------------------------------------------------
# --check: the peer is checked against independent references, so its timing is of a working
# chain. Tolerances are stated with each check.

def run_checks():
    rng = np.random.default_rng(2024)
    results = []

    def check(name, ok, detail):
        results.append(ok)
        print(f"{'ok  ' if ok else 'FAIL'} {name}: {detail}")

    def rel(a, b):
        return float(np.max(np.linalg.norm(a - b, axis=-1) / np.linalg.norm(b, axis=-1)))

    # 1. MWI closed form (the bench's operator G) against numpy.linalg.lstsq: a well-posed,
    # overdetermined system (64 bins of 12 x 8, condition < ~30) with exact data; alpha far below
    # sigma_min^2 makes phi = 1 - (alpha / (s^2 + alpha))^K indistinguishable from 1.
    bins, m, nn = 64, 12, 8
    hs = rng.standard_normal((bins, m, nn)) + 1j * rng.standard_normal((bins, m, nn))
    f_true = rng.standard_normal((bins, nn)) + 1j * rng.standard_normal((bins, nn))
    xs = np.matmul(hs, f_true[..., None])[..., 0] + 1e-3 * (
        rng.standard_normal((bins, m)) + 1j * rng.standard_normal((bins, m)))
    smin = np.linalg.svd(hs * np.sqrt(mwi_weights(hs))[:, None, :], compute_uv=False)[:, -1]
    g, _, _, _ = mwi_operator(hs, 50, alpha=1e-4 * smin.min() ** 2)
    f_mwi = np.matmul(g, xs[..., None])[..., 0]
    f_ls = np.stack([np.linalg.lstsq(hs[k], xs[k], rcond=None)[0] for k in range(bins)])
    err = rel(f_mwi, f_ls)
    check("MWI (K = 50, alpha << sigma_min^2) = lstsq", err < 1e-9, f"max relative error {err:.1e} "
          "(tolerance 1e-9)")

    # 2. The closed form against the literal iteration of Eqs. 40-43 at the bench's rule
    # (noise floor, eta = 1e-3, K = 50) on square 12 x 12 bins as in the bench.
    hs = rng.standard_normal((bins, 12, 12)) + 1j * rng.standard_normal((bins, 12, 12))
    xs = rng.standard_normal((bins, 12)) + 1j * rng.standard_normal((bins, 12))
    g, alpha, _, cond = mwi_operator(hs, 50, eta=1e-3)
    f_mwi = np.matmul(g, xs[..., None])[..., 0]
    f_it = mwi_by_iteration(hs, xs, alpha, 50)
    err = rel(f_mwi, f_it)
    check("MWI closed form = literal iteration (12 x 12, K = 50, noise floor)", err < 1e-8,
          f"max relative difference {err:.1e} over {bins} bins, max cond(H) {cond.max():.0f} "
          "(tolerance 1e-8)")

    # 3. The noise-floor rule: phi = 1/2 exactly at sigma = eta sigma_1.
    phi = mwi_filter(np.array([1e-3]), noise_floor_alpha(1.0, 1e-3, 50), 50)[0]
    check("noise-floor alpha gives phi(eta sigma_1) = 1/2", abs(phi - 0.5) < 1e-12,
          f"phi = {phi:.15f}")

    # 4. Squared envelope spectrum of an on-bin AM carrier: SES(fm) = 2m / (1 + m^2/2).
    n, fs = 16000, 8000.0
    t = np.arange(n) / fs
    depth = 0.5
    ses = squared_envelope_spectrum((1 + depth * np.cos(2 * np.pi * 10 * t))
                                    * np.cos(2 * np.pi * 1000 * t))
    want = 2 * depth / (1 + depth ** 2 / 2)
    got = ses[int(round(10 / (fs / n)))]
    check("SES of an AM carrier", abs(got - want) < 1e-9, f"{got:.12f} vs {want:.12f} "
          "(tolerance 1e-9)")

    # 4b. AR whitening: Levinson-Durbin's predictor solves the Toeplitz normal equations
    # (checked against numpy.linalg.solve on an AR(2) process plus a tone), and removes the tone.
    n, fs = 16000, 8000.0
    t = np.arange(n) / fs
    e = rng.standard_normal(n)
    ar = np.zeros(n)
    for i in range(2, n):
        ar[i] = 1.5 * ar[i - 1] - 0.8 * ar[i - 2] + e[i]
    xw = ar + 20 * np.cos(2 * np.pi * 280 * t)
    xw -= xw.mean()
    order = 16
    r = np.array([np.dot(xw[k:], xw[:n - k]) for k in range(order + 1)]) / n
    toeplitz = r[np.abs(np.arange(order)[:, None] - np.arange(order)[None, :])]
    toeplitz += np.eye(order) * r[0] * 1e-9
    coef = np.concatenate([[1.0], np.linalg.solve(toeplitz, -r[1:])])
    want_e = np.convolve(xw, coef)[:n]
    want_e[:order] = 0.0
    got_e = whiten(xw, order)
    err = np.linalg.norm(got_e - want_e) / np.linalg.norm(want_e)
    drop = np.var(got_e[order:]) / np.var(xw)
    check("AR whitening = Toeplitz solve", err < 1e-8 and drop < 0.05,
          f"relative difference {err:.1e} (tolerance 1e-8), variance kept {drop:.3f}")

    # 5. Kurtogram: Gaussian noise scores about 0 in the widest band (within 5 sigma) and no
    # significant band; decaying 2.5 kHz bursts at 17 Hz are found in a significant band.
    kp = KurtogramPlan(n, fs, 6, 120.0)
    noise = rng.standard_normal(n)
    kb = kp.process(noise)
    row0 = kp.rows[0]
    ok0 = not kb["significant"]
    check("kurtogram of Gaussian noise: nothing significant", ok0,
          f"best SK {kb['kurtosis']:.3f} at {kb['low_hz']:.0f}..{kb['high_hz']:.0f} Hz, "
          f"sigma {kb['sigma']:.3f}, {len(kp.rows)} rows, row 0 plan {row0['size']} points")
    bursts = np.zeros(n)
    for start in np.arange(0, n - 400, int(fs / 17)):
        k = np.arange(400)
        bursts[start:start + 400] += np.exp(-k / 40) * np.sin(2 * np.pi * 2500 * k / fs)
    kb = kp.process(0.1 * noise + 3 * bursts + np.cos(2 * np.pi * 280 * t))
    check("kurtogram finds 2.5 kHz bursts", kb["significant"] and kb["low_hz"] <= 2500
          <= kb["high_hz"], f"band {kb['low_hz']:.0f}..{kb['high_hz']:.0f} Hz, SK "
          f"{kb['kurtosis']:.1f} ({kb['kurtosis'] / kb['sigma']:.0f} sigma)")

    # 6. Synchronous average of two signals at once: a tone at order 28 of a 10 Hz shaft
    # (280 Hz = 0.035 fs) keeps its amplitude within the interpolation droop (under 0.02 %), a
    # 7 Hz tone (0.3 order off order 1) falls to |sin(0.3 pi R) / (R sin(0.3 pi))| = 0.053.
    sigs = np.stack([np.cos(2 * np.pi * 280 * t + 0.3), np.cos(2 * np.pi * 7 * t)])
    plan = tsa_plan(n, fs, 10.0, 1 << 14)
    _, orders, _ = tsa(np.ascontiguousarray(sigs.T), plan)
    a28, a1 = abs(orders[0, 28]), abs(orders[1, 1])
    r = plan["revolutions"]
    want1 = abs(np.sin(0.3 * np.pi * r) / (r * np.sin(0.3 * np.pi)))
    check("TSA: synchronous tone kept, asynchronous one averaged out",
          abs(a28 - 1) < 2e-4 and abs(a1 - want1) < 0.01 and plan["m"] == 1024 and r == 19,
          f"|order 28| = {a28:.6f} (tolerance 2e-4), 7 Hz tone at order 1: {a1:.4f} vs "
          f"{want1:.4f} (tolerance 0.01), M = {plan['m']}, R = {r}")

    # 7. The whole chain on small shapes: runs, finite, residual small, a dominant path named.
    freq, h = reference_frf(6, 6, 2001, 4000.0, seed=3)
    chain = Chain(freq, h, 4000).configure()
    block = reference_block(6, 4000)
    out = chain.process(block)
    chain.learn(out)
    out = chain.process(block)
    finite = all(np.all(np.isfinite(v)) for v in out["indicators"])
    check("chain on 6 x 6 paths, 4000 samples", finite and 0 <= out["dominant_path"] < 6
          and out["relative_residual"] < 1e-2 and abs(out["score"]) < 1e-9,
          f"dominant path {out['dominant_path']}, relative residual "
          f"{out['relative_residual']:.1e}, score vs its own baseline {out['score']:.1e}")

    # 8. Transient gate, as the C++ tests (tests/core/dsp/transient_gate_test.cc). (a) Two
    # decaying bursts among noise and pump tones: without them nothing is marked; with them
    # nothing is taken before the first one's guard window, and over each one's first five time
    # constants under 10 % of its energy is left. (b) A shaft's mesh harmonics (orders 28 and 56
    # of 10 Hz) less its revolution median read back: under 1 % of the RMS left anywhere away
    # from the ends (the interpolation's accuracy).
    n, fs = 16000, 8000.0
    t = np.arange(n) / fs
    base = 0.05 * rng.standard_normal(n)
    for f in (331.0, 597.5, 1204.0):
        base += 0.7 * np.cos(2 * np.pi * f * t + 0.3 * f)
    bursts = np.zeros(n)
    for at, peak, f, tau in ((4001, 1.5, 1800.0, 4e-3), (9517, 1.0, 900.0, 6e-3)):
        k = np.arange(int(12 * tau * fs))
        bursts[at:at + k.size] += peak * np.exp(-k / fs / tau) * np.sin(2 * np.pi * f * k / fs)
    _, quiet = gate_estimate(base[:, None], fs)
    taken, marked = gate_estimate((base + bursts)[:, None], fs)
    left = bursts - taken[:, 0]

    def energy(v, a, b):
        return float(np.sum(v[a:b] ** 2))

    ratios = [energy(left, a, a + int(5 * tau * fs)) / energy(bursts, a, a + int(5 * tau * fs))
              for a, tau in ((4001, 4e-3), (9517, 6e-3))]
    check("transient gate takes out the bursts and nothing else",
          quiet[0] == 0 and 0 < marked[0] < n // 4 and energy(taken[:, 0], 0, 3984) == 0.0
          and max(ratios) < 0.1,
          f"marked {quiet[0]} samples without the bursts, {marked[0]} with them; energy left "
          f"of each burst {ratios[0]:.3f}, {ratios[1]:.3f} (tolerance 0.1)")
    tones = np.cos(2 * np.pi * 280.0 * t + 0.2) + 0.6 * np.cos(2 * np.pi * 560.0 * t + 0.4)
    rest = subtract_shafts(tones[:, None], [tsa_plan(n, fs, 10.0, 1 << 16)], [10.0], fs)
    worst = float(np.max(np.abs(rest[100:n - 100, 0])) / np.sqrt(np.mean(tones ** 2)))
    check("the revolution median takes out the shaft's tones", worst < 0.01,
          f"largest remnant {worst:.2e} of the RMS (tolerance 0.01)")

    failed = results.count(False)
    print(f"numpy_peer: {len(results) - failed} passed, {failed} failed")
    return 1 if failed else 0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--check", action="store_true", help="run the correctness checks and exit")
    p.add_argument("--reps", type=int, default=20, help="timed blocks (median reported)")
    p.add_argument("--warmup", type=int, default=3, help="blocks before timing (first = baseline)")
    p.add_argument("--precompute-reps", type=int, default=3, help="timed precomputes")
    p.add_argument("--json", metavar="FILE", help="also write the figures as JSON")
    args = p.parse_args()
    if args.check:
        return run_checks()
    return run_benchmark(args)


if __name__ == "__main__":
    sys.exit(main())
