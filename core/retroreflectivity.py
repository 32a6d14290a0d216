"""LiDAR intensity normalised for range and incidence; the bright threshold; sign condition.

**Intensity model.** A return's recorded intensity is taken as

    I = I_full * rho * g(theta) * (r_ref / r) ** alpha

with ``rho`` the surface's reflectance at the laser's wavelength, ``r`` the range from the
sensor (the track interpolated at the point's time, see :mod:`.drivewindows`), ``theta`` the
incidence angle between the beam and the surface normal, ``I_full`` the file's full scale
(65535 for 16-bit LAS intensity). The normalised intensity is the reflectance estimate

    I_n = I / I_full * (r / r_ref) ** alpha / max(cos theta, cos theta_max) ** beta

* ``alpha`` (range exponent) is estimated from the cloud itself: the returns are binned by
  range, the bright mode (retroreflective sheeting, whose reflectance is nearly the same on
  every sign) is found in each bin on its own (as the threshold below), and ``alpha`` is
  minus the slope of its median log-intensity against log-range (least squares over the
  bins with a bright mode of at least 200 returns below saturation, weighted by the square
  root of their counts, clipped to ``[0, 3]``). Scanners that already compensate range
  give ``alpha`` ~ 0; raw amplitudes ~ 2. Fewer than :data:`MIN_RANGE_BINS` usable bins
  (sheeting saturating the receiver, a short drive): ``alpha`` = 0 (no range correction),
  said in the log.
* ``beta`` = 1 (Lambertian). Retroreflective sheeting returns light towards the source
  over a wide range of entrance angles, better than a diffuse surface, so the correction
  over-corrects bright sheeting seen obliquely; ``theta`` is capped at ``theta_max`` = 60
  degrees so that a face scanned at a grazing angle is corrected at most 2 times.
* ``r_ref`` = 10 m: ``I_n`` is the intensity the return would have at 10 m, head on.

**Threshold.** Retroreflective points are those with range-normalised intensity above a
threshold adapted to the cloud, from the histogram of log-intensity of the non-ground points
in the corridor (filled while streaming, :class:`IntensityHistogram`, smoothed over 1/8
octave): a robust background level ``B = median + 4 MAD``; the bright mode is the highest
peak above both ``B`` and one octave over the main mode, holding at least 50 returns (and
0.1 %); the threshold is the bottom of the valley between the main mode and the bright mode
(the middle of it when flat). No bright mode (a drive without sheeting): the threshold is
``B``; no return above ``B`` at all: Otsu's threshold over all returns. The log states the
threshold, the levels and the method.

**Condition.** ``retro_index`` is the median normalised intensity of the face's interior
points (points within an edge margin of the outline are left out: their footprints fall
partly off the panel). It is compared with a reference: ``retro_reference`` when given (a
calibrated scanner), else the median ``retro_index`` of the drive's retroreflective panels
(at least :data:`MIN_REFERENCE_PANELS`; a drive is assumed to hold mostly healthy signs),
else 1.5 x the threshold. ``good``: at least ``good_ratio`` (0.6) of the reference;
``poor``: below ``poor_ratio`` (0.35); ``check`` between; ``unknown`` when the scanner saw
only the back of the panel.

Limits: this is a screening flag from a laser at near-infrared, at the scanner's own
observation and entrance angles, not a retroreflectivity measurement under the MUTCD /
ASTM E1709 geometry (0.2 degree observation, -4 degree entrance angle, white light); wet,
dirty or dew-covered faces and the scanner's own non-linearity (saturation) affect it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np
from scipy.ndimage import gaussian_filter1d

#: Full scale of LAS 16-bit intensity.
INTENSITY_FULL_SCALE = 65535.0
#: ``I_n`` is referred to this range, metres.
REFERENCE_RANGE_M = 10.0
#: Log2-intensity histogram: bins per octave and octaves below full scale.
BINS_PER_OCTAVE = 32
OCTAVES = 16
#: Range bins of the histogram (log-spaced), metres.
RANGE_BIN_EDGES_M = np.geomspace(0.5, 200.0, 41)
#: A range bin needs this many bright returns to enter the range-exponent fit.
MIN_BRIGHT_PER_RANGE_BIN = 200
MIN_RANGE_BINS = 3
RANGE_EXPONENT_LIMITS = (0.0, 3.0)
#: A range bin enters the fit with this many returns, its bright mode below full scale by this.
MIN_POINTS_PER_RANGE_BIN = 1000
SATURATION_MARGIN_OCTAVES = 0.125
#: Background level: median + this many MADs (scaled to sigma) of log-intensity.
BACKGROUND_MADS = 4.0
#: A bright mode holds at least this many returns (count, share) ...
MIN_TAIL_POINTS = 50
MIN_TAIL_SHARE = 0.001
#: ... above the background level and this many octaves above the main mode.
MIN_BRIGHT_OCTAVES = 1.0
#: Gaussian smoothing of the log-intensity histogram, bins.
SMOOTHING_BINS = 4.0
METHOD_VALLEY, METHOD_BACKGROUND, METHOD_OTSU, METHOD_NONE = "valley", "background", "otsu", "none"
#: Share of non-ground returns at full scale / at zero above which the log warns.
SATURATED_SHARE_WARNING = 0.2
ZERO_SHARE_WARNING = 0.5
#: Condition values and the ratios to the reference that separate them.
GOOD, CHECK, POOR, UNKNOWN = "good", "check", "poor", "unknown"
CONDITIONS = (GOOD, CHECK, POOR, UNKNOWN)
GOOD_RATIO = 0.6
POOR_RATIO = 0.35
#: The drive's own reference needs this many retroreflective panels seen from the front.
MIN_REFERENCE_PANELS = 3
#: Without it: reference = this x the bright threshold.
FALLBACK_REFERENCE_FACTOR = 1.5
INCIDENCE_EXPONENT = 1.0
MAX_INCIDENCE_DEG = 60.0


@dataclass
class IntensityModel:
    """The normalisation ``I_n = I / full_scale * (r / r_ref)^alpha / max(cos, cos_max)^beta``."""

    range_exponent: float = 0.0
    reference_range_m: float = REFERENCE_RANGE_M
    incidence_exponent: float = INCIDENCE_EXPONENT
    max_incidence_deg: float = MAX_INCIDENCE_DEG
    full_scale: float = INTENSITY_FULL_SCALE

    def range_normalised(self, intensity, range_m) -> np.ndarray:
        """Intensity corrected for range only (no incidence), in units of full scale."""
        r = np.maximum(np.asarray(range_m, dtype=np.float64), 0.1)
        return (np.asarray(intensity, dtype=np.float64) / self.full_scale
                * (r / self.reference_range_m) ** self.range_exponent)

    def normalised(self, intensity, range_m, cos_incidence) -> np.ndarray:
        """Intensity corrected for range and incidence (``cos_incidence`` = |cos theta|)."""
        floor = math.cos(math.radians(self.max_incidence_deg))
        c = np.maximum(np.abs(np.asarray(cos_incidence, dtype=np.float64)), floor)
        return self.range_normalised(intensity, range_m) / c ** self.incidence_exponent


def otsu_threshold(counts: np.ndarray, centres: np.ndarray) -> float:
    """Otsu's threshold of a histogram (``counts`` at bin ``centres``): the value between
    the bins that maximises the between-class variance."""
    counts = np.asarray(counts, dtype=np.float64)
    centres = np.asarray(centres, dtype=np.float64)
    if counts.sum() <= 0 or len(counts) < 2:
        return float(centres[-1]) if len(centres) else 0.0
    w0 = np.cumsum(counts)
    w1 = w0[-1] - w0
    s0 = np.cumsum(counts * centres)
    m0 = s0 / np.maximum(w0, 1e-12)
    m1 = (s0[-1] - s0) / np.maximum(w1, 1e-12)
    between = w0 * w1 * (m0 - m1) ** 2
    k = int(np.argmax(between[:-1]))
    return float(0.5 * (centres[k] + centres[k + 1]))


def _weighted_quantile(values: np.ndarray, weights: np.ndarray, q: float) -> float:
    order = np.argsort(values)
    cum = np.cumsum(weights[order])
    if cum[-1] <= 0:
        return float("nan")
    return float(values[order][np.searchsorted(cum, q * cum[-1])])


@dataclass
class Threshold:
    """The bright threshold and how it was found (for the log)."""

    value: float                  # range-normalised intensity (share of full scale)
    background: float             # median + 4 MAD level
    bright_mode: float            # the peak of the bright returns
    method: str                   # valley, background (no bright mode) or otsu
    range_exponent: float
    range_bins_used: int
    n_points: int
    zero_share: float
    saturated_share: float


class IntensityHistogram:
    """Log2-intensity histogram of returns by range bin, filled chunk by chunk.

    Intensities are in units of full scale and not range-corrected; zero and full-scale
    returns are counted apart (they say nothing about the log-intensity).
    """

    def __init__(self, full_scale: float = INTENSITY_FULL_SCALE):
        self.full_scale = float(full_scale)
        self.n_bins = BINS_PER_OCTAVE * OCTAVES
        self.counts = np.zeros((len(RANGE_BIN_EDGES_M) - 1, self.n_bins), np.int64)
        self.n_total = 0
        self.n_zero = 0
        self.n_saturated = 0

    @property
    def log2_centres(self) -> np.ndarray:
        """Bin centres in log2(intensity / full scale)."""
        return -OCTAVES + (np.arange(self.n_bins) + 0.5) / BINS_PER_OCTAVE

    @property
    def range_centres_m(self) -> np.ndarray:
        return np.sqrt(RANGE_BIN_EDGES_M[:-1] * RANGE_BIN_EDGES_M[1:])

    def add(self, intensity, range_m) -> None:
        raw = np.asarray(intensity, dtype=np.float64)
        self.n_total += len(raw)
        zero = raw <= 0
        saturated = raw >= self.full_scale
        self.n_zero += int(zero.sum())
        self.n_saturated += int(saturated.sum())
        ok = ~zero
        if not ok.any():
            return
        value = np.log2(np.minimum(raw[ok], self.full_scale) / self.full_scale)
        col = np.clip(((value + OCTAVES) * BINS_PER_OCTAVE).astype(np.int64), 0, self.n_bins - 1)
        row = np.clip(np.searchsorted(RANGE_BIN_EDGES_M, np.asarray(range_m)[ok]) - 1, 0,
                      len(RANGE_BIN_EDGES_M) - 2)
        np.add.at(self.counts, (row, col), 1)

    def _shifted(self, range_exponent: float) -> np.ndarray:
        """The histogram of range-normalised log-intensity (whole bins shifted per range)."""
        shift = range_exponent * np.log2(self.range_centres_m / REFERENCE_RANGE_M)
        out = np.zeros(self.n_bins + 2 * OCTAVES * BINS_PER_OCTAVE, np.int64)
        base = OCTAVES * BINS_PER_OCTAVE
        for i, row in enumerate(self.counts):
            if row.any():
                k = base + int(round(shift[i] * BINS_PER_OCTAVE))
                out[k:k + self.n_bins] += row
        return out

    def _threshold_log2(self, range_exponent: float) -> Tuple[float, float, float, str]:
        """(threshold, background, bright mode, method) in log2 of range-normalised
        intensity; see the module's doc."""
        counts = self._shifted(range_exponent).astype(np.float64)
        centres = -2 * OCTAVES + (np.arange(len(counts)) + 0.5) / BINS_PER_OCTAVE
        return _bright_cut(counts, centres)

    def _range_exponent(self) -> Tuple[float, int]:
        """Minus the slope of the bright mode's median log2-intensity against log2-range over
        the range bins that have their own bright mode (found in each bin alone, so without
        knowing the exponent), weighted by the square root of their bright counts; bins whose
        bright returns saturate are left out."""
        centres = self.log2_centres
        xs, ys, ws = [], [], []
        for i, row in enumerate(self.counts):
            if row.sum() < MIN_POINTS_PER_RANGE_BIN:
                continue
            cut, _, _, method = _bright_cut(row.astype(np.float64), centres)
            bright = centres >= cut
            n = int(row[bright].sum())
            if method != METHOD_VALLEY or n < MIN_BRIGHT_PER_RANGE_BIN:
                continue
            median = _weighted_quantile(centres[bright], row[bright].astype(float), 0.5)
            if median >= -SATURATION_MARGIN_OCTAVES:
                continue
            xs.append(math.log2(self.range_centres_m[i]))
            ys.append(median)
            ws.append(math.sqrt(n))
        if len(xs) < MIN_RANGE_BINS:
            return 0.0, len(xs)
        slope = float(np.polyfit(np.asarray(xs), np.asarray(ys), 1, w=np.asarray(ws))[0])
        lo, hi = RANGE_EXPONENT_LIMITS
        return float(min(max(-slope, lo), hi)), len(xs)

    def threshold(self, range_exponent: Optional[float] = None) -> Threshold:
        """The adaptive bright threshold; ``range_exponent`` ``None``: estimated first."""
        bins_used = 0
        if range_exponent is None:
            alpha, bins_used = self._range_exponent()
        else:
            alpha = float(range_exponent)
        value, background, mode, method = self._threshold_log2(alpha)
        n = max(self.n_total, 1)
        return Threshold(value=2.0 ** value, background=2.0 ** background, bright_mode=2.0 ** mode,
                         method=method, range_exponent=alpha, range_bins_used=bins_used,
                         n_points=self.n_total, zero_share=self.n_zero / n,
                         saturated_share=self.n_saturated / n)


def _bright_cut(counts: np.ndarray, centres: np.ndarray) -> Tuple[float, float, float, str]:
    """(threshold, background, bright mode, method) of a log2-intensity histogram."""
    total = counts.sum()
    if total == 0:
        return 0.0, 0.0, 0.0, METHOD_NONE
    median = _weighted_quantile(centres, counts, 0.5)
    mad = _weighted_quantile(np.abs(centres - median), counts, 0.5) * 1.4826
    background = median + BACKGROUND_MADS * max(mad, 1.0 / BINS_PER_OCTAVE)
    smooth = gaussian_filter1d(counts, SMOOTHING_BINS, mode="constant")
    main = int(np.argmax(smooth))
    above = centres > max(background, centres[main] + MIN_BRIGHT_OCTAVES)
    if counts[above].sum() < max(MIN_TAIL_POINTS, MIN_TAIL_SHARE * total):
        if counts[centres > background].sum() > 0:
            return background, background, background, METHOD_BACKGROUND   # no bright mode
        otsu = otsu_threshold(counts, centres)       # the background swallows everything
        return otsu, background, otsu, METHOD_OTSU
    peak = int(np.flatnonzero(above)[np.argmax(smooth[above])])
    between = smooth[main:peak + 1]
    low = np.flatnonzero(between <= between.min() + 1e-9)
    valley = main + int(round(0.5 * (low[0] + low[-1])))   # the middle of a flat valley
    return float(centres[valley]), background, float(centres[peak]), METHOD_VALLEY


def retro_index(normalised_intensity: np.ndarray, interior: np.ndarray,
                min_points: int = 10) -> float:
    """Median normalised intensity of the interior face points (all face points when fewer
    than ``min_points`` are interior); NaN without points."""
    values = np.asarray(normalised_intensity, dtype=np.float64)
    inner = values[np.asarray(interior, dtype=bool)]
    use = inner if len(inner) >= min_points else values
    return float(np.median(use)) if len(use) else float("nan")


def drive_reference(indices: np.ndarray, threshold: float,
                    retro_reference: Optional[float] = None) -> Tuple[float, str]:
    """The reference the condition compares with, and where it came from (for the log):
    ``retro_reference`` when given, else the median of the retroreflective panels'
    ``indices`` (at least :data:`MIN_REFERENCE_PANELS`), else 1.5 x the threshold."""
    if retro_reference is not None and retro_reference > 0:
        return float(retro_reference), "given"
    values = np.asarray(indices, dtype=np.float64)
    values = values[np.isfinite(values)]
    if len(values) >= MIN_REFERENCE_PANELS:
        return float(np.median(values)), "drive"
    return FALLBACK_REFERENCE_FACTOR * float(threshold), "threshold"


def condition_of(index: float, reference: float, face_seen: bool,
                 good_ratio: float = GOOD_RATIO, poor_ratio: float = POOR_RATIO) -> str:
    """``good`` / ``check`` / ``poor`` from ``index / reference``; ``unknown`` when the face
    was not scanned or has no index."""
    if not face_seen or not math.isfinite(index) or reference <= 0:
        return UNKNOWN
    ratio = index / reference
    if ratio >= good_ratio:
        return GOOD
    if ratio < poor_ratio:
        return POOR
    return CHECK
