"""Irregular waves and turbulent wind of one sea state, seeded per case.

Waves are long-crested JONSWAP seas; wind is a single-point hub-height turbulent series from
the NPD (Froya) spectrum of DNV-RP-C205 or from a Kaimal spectrum. Everything is built from
random phases drawn from ``conventions.case_rng(seed, mooring_system, case_id)``, so a sea
state's realisation depends on nothing else.

Conventions
-----------
Complex amplitudes follow Capytaine's ``exp(-i omega t)`` convention: a wave component of
complex amplitude ``A`` travelling along the propagation angle ``theta`` (radians, counter-
clockwise from east, see :func:`moorlife.conventions.propagation_angle`) has elevation
``eta(x, y, t) = Re(A exp(i (k (x cos theta + y sin theta) - omega t)))`` and excites the
platform with ``F(t) = Re(X(omega, theta) A exp(-i omega t))`` where ``X`` is the BEM
excitation per metre of amplitude at the origin.

Synthesis is by FFT on a regular frequency grid ``omega_k = k * d_omega``, with
``d_omega = 2 pi / (N dt)`` and ``N dt`` at least the simulated length, so the record never
repeats. A component series ``s(t) = Re(sum_k C_k exp(-i omega_k t))`` is
``irfft(N / 2 * conj(C))`` (:func:`synthesise`).

The default JONSWAP peak enhancement is the DNV-RP-C205 (sec. 3.5.5.5) rule on
``Tp / sqrt(Hs)``: 5 for steep wind seas, 1 (Pierson-Moskowitz) for swell, between them
``exp(5.75 - 1.15 Tp / sqrt(Hs))``. It adapts gamma to each of the hindcast's sea states, which
mix wind sea and swell; a fixed value (3.3, or the paper's validation 2.2) is a config switch.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
import scipy.fft

from moorlife.conventions import case_rng, propagation_angle
from moorlife.settings import WindSettings

__all__ = [
    "G",
    "dnv_gamma",
    "resolve_gamma",
    "jonswap",
    "wave_number",
    "npd_mean_speed_10m",
    "npd_spectrum",
    "kaimal_spectrum",
    "wind_spectrum",
    "wind_settings",
    "record_grid",
    "RecordGrid",
    "wave_components",
    "WaveComponents",
    "synthesise",
    "synthesise_complex",
    "wind_series",
    "case_streams",
]

#: Standard gravity, m s-2.
G = 9.80665


def dnv_gamma(hs: npt.ArrayLike, tp: npt.ArrayLike) -> np.ndarray:
    """JONSWAP peak-enhancement factor from the DNV-RP-C205 rule (sec. 3.5.5.5).

    Parameters
    ----------
    hs, tp : array_like
        Significant wave height (m) and peak period (s), broadcastable.

    Returns
    -------
    numpy.ndarray
        ``gamma = 5`` for ``Tp/sqrt(Hs) <= 3.6``, ``1`` for ``>= 5``, else
        ``exp(5.75 - 1.15 Tp/sqrt(Hs))``.
    """
    hs = np.asarray(hs, dtype=float)
    tp = np.asarray(tp, dtype=float)
    phi = tp / np.sqrt(np.maximum(hs, 1e-12))
    return np.where(phi <= 3.6, 5.0, np.where(phi >= 5.0, 1.0, np.exp(5.75 - 1.15 * phi)))


def resolve_gamma(rule: str | float, hs: npt.ArrayLike, tp: npt.ArrayLike) -> np.ndarray:
    """Peak-enhancement factor per sea state from the config value (``"dnv"`` or a number >= 1)."""
    hs = np.asarray(hs, dtype=float)
    if isinstance(rule, str):
        if rule.lower() != "dnv":
            raise ValueError(f"simulation.gamma = {rule!r}: expected 'dnv' or a number >= 1")
        return dnv_gamma(hs, tp)
    g = float(rule)
    if not g >= 1.0:
        raise ValueError(f"simulation.gamma = {rule!r}: a JONSWAP gamma must be >= 1")
    return np.full(np.broadcast(hs, np.asarray(tp)).shape, g)


def jonswap(omega: npt.ArrayLike, hs: npt.ArrayLike, tp: npt.ArrayLike, gamma: npt.ArrayLike) -> np.ndarray:
    """One-sided JONSWAP spectral density (DNV-RP-C205 eq. 3.5.5.2).

    Parameters
    ----------
    omega : array_like, shape (nw,)
        Angular frequency, rad/s (> 0).
    hs, tp, gamma : array_like, shape (...)
        Significant wave height (m), peak period (s) and peak enhancement (-).

    Returns
    -------
    numpy.ndarray, shape (..., nw)
        ``S(omega)`` in m2 s/rad, normalised with Goda's ``A = 1 - 0.287 ln(gamma)`` so that
        ``4 sqrt(m0) = Hs`` within about 1 % for ``1 <= gamma <= 7``.
    """
    w = np.asarray(omega, dtype=float)
    hs = np.asarray(hs, dtype=float)[..., None]
    wp = 2.0 * np.pi / np.asarray(tp, dtype=float)[..., None]
    gamma = np.asarray(gamma, dtype=float)[..., None]
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        pm = 5.0 / 16.0 * hs**2 * wp**4 * w**-5.0 * np.exp(-1.25 * (w / wp) ** -4.0)
        sigma = np.where(w <= wp, 0.07, 0.09)
        peak = gamma ** np.exp(-0.5 * ((w - wp) / (sigma * wp)) ** 2)
        s = (1.0 - 0.287 * np.log(gamma)) * pm * peak
    return np.where(w > 0, s, 0.0)


def wave_number(omega: npt.ArrayLike, depth: float) -> np.ndarray:
    """Linear wave number from ``omega^2 = g k tanh(k h)`` (Newton iterations), rad/m."""
    w = np.asarray(omega, dtype=float)
    if not np.isfinite(depth) or depth <= 0:
        return w**2 / G
    k = np.maximum(w**2 / G, w / np.sqrt(G * depth))
    for _ in range(50):
        th = np.tanh(k * depth)
        f = G * k * th - w**2
        df = G * th + G * k * depth * (1.0 - th**2)
        step = np.where(df > 0, f / np.where(df > 0, df, 1.0), 0.0)
        k = k - step
        if np.all(np.abs(step) <= 1e-12 * np.maximum(k, 1e-12)):
            break
    return k


def npd_mean_speed_10m(u_z: npt.ArrayLike, z: float) -> np.ndarray:
    """Invert the NPD mean profile ``U(z) = U0 (1 + C ln(z/10))``, ``C = 0.0573 sqrt(1 + 0.148 U0)``.

    Parameters
    ----------
    u_z : array_like
        One-hour mean wind speed at height ``z`` (m/s).
    z : float
        Height above sea level, m.

    Returns
    -------
    numpy.ndarray
        The one-hour mean at 10 m, ``U0`` (m/s), by fixed-point iteration.
    """
    u_z = np.asarray(u_z, dtype=float)
    lnz = np.log(z / 10.0)
    u0 = u_z / (1.0 + 0.0573 * lnz)
    for _ in range(60):
        u0 = u_z / (1.0 + 0.0573 * np.sqrt(1.0 + 0.148 * u0) * lnz)
    return u0


def npd_spectrum(f: npt.ArrayLike, u_hub: npt.ArrayLike, z: float) -> np.ndarray:
    """NPD (Froya) spectrum of longitudinal wind at height ``z`` (DNV-RP-C205 eq. 2.3.2.12).

    Parameters
    ----------
    f : array_like, shape (nf,)
        Frequency, Hz.
    u_hub : array_like, shape (...)
        One-hour mean wind speed at height ``z``, m/s.
    z : float
        Height, m.

    Returns
    -------
    numpy.ndarray, shape (..., nf)
        ``S(f) = 320 (U0/10)^2 (z/10)^0.45 / (1 + f~^n)^(5/(3n))`` in m2 s-2 Hz-1, with
        ``f~ = 172 f (z/10)^(2/3) (U0/10)^-0.75``, ``n = 0.468`` and ``U0`` the 10-m mean from
        :func:`npd_mean_speed_10m`.
    """
    f = np.asarray(f, dtype=float)
    u0 = np.maximum(npd_mean_speed_10m(u_hub, z), 1e-6)[..., None]
    n = 0.468
    ft = 172.0 * f * (z / 10.0) ** (2.0 / 3.0) * (u0 / 10.0) ** -0.75
    return 320.0 * (u0 / 10.0) ** 2 * (z / 10.0) ** 0.45 / (1.0 + ft**n) ** (5.0 / (3.0 * n))


def kaimal_spectrum(
    f: npt.ArrayLike, u_hub: npt.ArrayLike, turbulence_intensity: float, length_scale: float
) -> np.ndarray:
    """Kaimal spectrum of longitudinal wind (IEC 61400-1 ed. 3, annex B).

    Parameters
    ----------
    f : array_like, shape (nf,)
        Frequency, Hz.
    u_hub : array_like, shape (...)
        Mean hub-height wind speed, m/s.
    turbulence_intensity : float
        ``sigma_u / U``, -.
    length_scale : float
        Integral scale ``L_u`` in m (IEC: 8.1 * 42 = 340.2 m above 60 m height).

    Returns
    -------
    numpy.ndarray, shape (..., nf)
        ``S(f) = sigma^2 4 L/U / (1 + 6 f L/U)^(5/3)``, m2 s-2 Hz-1.
    """
    f = np.asarray(f, dtype=float)
    u = np.maximum(np.asarray(u_hub, dtype=float), 1e-6)[..., None]
    sigma = turbulence_intensity * u
    tl = length_scale / u
    return sigma**2 * 4.0 * tl / (1.0 + 6.0 * f * tl) ** (5.0 / 3.0)


def wind_settings(cfg: Mapping[str, Any]) -> WindSettings:
    """The ``simulation.wind`` section (without the ``height`` the simulator adds), schema-filled."""
    return WindSettings.from_config({k: v for k, v in cfg.items() if k != "height"}, source="config.yaml")


def wind_spectrum(f: npt.ArrayLike, u_hub: npt.ArrayLike, cfg: dict) -> np.ndarray:
    """The configured wind spectrum (``cfg`` is the ``simulation.wind`` config section).

    Missing keys take the schema defaults; ``height`` (hub height, m) is needed by ``npd``.

    Returns
    -------
    numpy.ndarray, shape (..., nf)
        m2 s-2 Hz-1; zero everywhere when ``cfg["spectrum"] == "none"`` (steady wind).
    """
    w = wind_settings(cfg)
    kind = w.spectrum
    if kind == "npd":
        if "height" not in cfg:
            raise ValueError("simulation.wind: the NPD spectrum needs the hub 'height' in m")
        return npd_spectrum(f, u_hub, float(cfg["height"]))
    if kind == "kaimal":
        return kaimal_spectrum(f, u_hub, w.turbulence_intensity, w.length_scale)
    if kind == "none":
        return np.zeros(np.shape(u_hub) + np.shape(f))
    raise ValueError(f"simulation.wind.spectrum = {kind!r}: expected 'npd', 'kaimal' or 'none'")


@dataclass(frozen=True)
class RecordGrid:
    """Time and frequency grid of one simulated record.

    Attributes
    ----------
    dt : float
        Sample step, s.
    n_steps : int
        Number of integration steps (``(transient + duration) / dt``, rounded up).
    n_fft : int
        FFT length (>= n_steps + 1), so the synthesised record does not repeat.
    d_omega : float
        Frequency resolution ``2 pi / (n_fft dt)``, rad/s.
    """

    dt: float
    n_steps: int
    n_fft: int
    d_omega: float

    @property
    def omega(self) -> np.ndarray:
        """Positive FFT frequencies ``k d_omega``, ``k = 0 .. n_fft // 2`` (rad/s)."""
        return np.arange(self.n_fft // 2 + 1) * self.d_omega


def record_grid(duration: float, transient: float, dt: float) -> RecordGrid:
    """The grid of a record of ``transient + duration`` seconds at step ``dt``."""
    if dt <= 0 or duration <= 0 or transient < 0:
        raise ValueError(f"bad record: duration={duration}, transient={transient}, dt={dt}")
    n_steps = int(np.ceil((duration + transient) / dt - 1e-9))
    n_fft = scipy.fft.next_fast_len(n_steps + 1, real=True)
    if n_fft % 2:
        n_fft += 1
    return RecordGrid(dt=float(dt), n_steps=n_steps, n_fft=n_fft, d_omega=2.0 * np.pi / (n_fft * dt))


@dataclass(frozen=True)
class WaveComponents:
    """Complex wave amplitudes of a batch of sea states on an FFT grid.

    Attributes
    ----------
    index : numpy.ndarray, shape (nk,)
        FFT bins ``k`` of the components (``omega = k * grid.d_omega``).
    omega : numpy.ndarray, shape (nk,)
        Their angular frequencies, rad/s.
    amplitude : numpy.ndarray, shape (B, nk), complex
        ``A_k = sqrt(2 S(omega_k) d_omega) exp(i phi_k)``, m.
    theta : numpy.ndarray, shape (B,)
        Propagation angle, rad.
    """

    index: np.ndarray
    omega: np.ndarray
    amplitude: np.ndarray
    theta: np.ndarray


def wave_components(
    grid: RecordGrid,
    hs: npt.ArrayLike,
    tp: npt.ArrayLike,
    wave_dir: npt.ArrayLike,
    gamma: npt.ArrayLike,
    phases: np.ndarray,
    *,
    omega_min: float,
    omega_max: float,
) -> WaveComponents:
    """Long-crested JONSWAP components of a batch of sea states.

    Parameters
    ----------
    grid : RecordGrid
        The record's FFT grid.
    hs, tp, wave_dir, gamma : array_like, shape (B,)
        Hs (m), Tp (s), nautical direction the waves come from (deg), JONSWAP gamma.
    phases : numpy.ndarray, shape (B, n_fft // 2 + 1)
        Random phases in ``[0, 2 pi)`` for every FFT bin (see :func:`case_streams`); only the
        bins inside ``[omega_min, omega_max]`` are used, so the phase of a bin does not depend
        on the cut-offs.
    omega_min, omega_max : float
        Band kept, rad/s (the BEM frequency range).

    Returns
    -------
    WaveComponents
    """
    w_all = grid.omega
    keep = np.flatnonzero((w_all >= omega_min) & (w_all <= omega_max) & (w_all > 0))
    w = w_all[keep]
    s = jonswap(w, hs, tp, gamma)
    amp = np.sqrt(2.0 * s * grid.d_omega) * np.exp(1j * phases[:, keep])
    theta = propagation_angle(np.asarray(wave_dir, dtype=float))
    return WaveComponents(index=keep, omega=w, amplitude=amp, theta=np.atleast_1d(theta))


def synthesise(coeff: np.ndarray, index: np.ndarray, grid: RecordGrid, *, n: int | None = None) -> np.ndarray:
    """Real series ``s(t_j) = Re(sum_k C_k exp(-i omega_k t_j))``, ``t_j = j dt``, by inverse FFT.

    Parameters
    ----------
    coeff : numpy.ndarray, shape (..., nk), complex
        Complex amplitudes ``C_k`` at the FFT bins ``index``.
    index : numpy.ndarray, shape (nk,)
        FFT bins of the components.
    grid : RecordGrid
    n : int, optional
        Samples returned (default ``grid.n_steps + 1``).

    Returns
    -------
    numpy.ndarray, shape (..., n)
    """
    n = grid.n_steps + 1 if n is None else n
    spec = np.zeros(coeff.shape[:-1] + (grid.n_fft // 2 + 1,), dtype=complex)
    spec[..., index] = np.conj(coeff) * (grid.n_fft / 2.0)
    return scipy.fft.irfft(spec, n=grid.n_fft, axis=-1)[..., :n]


def synthesise_complex(coeff: np.ndarray, index: np.ndarray, grid: RecordGrid, *, n: int | None = None) -> np.ndarray:
    """Complex envelope ``a(t_j) = sum_k C_k exp(-i omega_k t_j)`` (its real part is :func:`synthesise`).

    Used for Newman's slow drift, whose difference-frequency part is ``|a(t)|^2``.

    Returns
    -------
    numpy.ndarray, shape (..., n), complex
    """
    n = grid.n_steps + 1 if n is None else n
    spec = np.zeros(coeff.shape[:-1] + (grid.n_fft,), dtype=complex)
    spec[..., index] = coeff
    return scipy.fft.fft(spec, axis=-1)[..., :n]


def wind_series(grid: RecordGrid, u_hub: npt.ArrayLike, phases: np.ndarray, cfg: dict) -> np.ndarray:
    """Turbulent hub-height longitudinal wind speed of a batch of sea states.

    Parameters
    ----------
    grid : RecordGrid
    u_hub : array_like, shape (B,)
        One-hour mean wind speed at hub height, m/s.
    phases : numpy.ndarray, shape (B, n_fft // 2 + 1)
        Random phases (see :func:`case_streams`).
    cfg : dict
        The ``simulation.wind`` section: ``spectrum``, ``height``, ``turbulence_intensity``,
        ``length_scale``, ``f_max`` (Hz, highest frequency kept).

    Returns
    -------
    numpy.ndarray, shape (B, n_steps + 1)
        Wind speed, m/s, at ``t_j = j dt``; its mean over the whole FFT period is ``u_hub``.
    """
    u = np.atleast_1d(np.asarray(u_hub, dtype=float))
    w = grid.omega
    f = w / (2.0 * np.pi)
    keep = np.flatnonzero((f > 0) & (f <= wind_settings(cfg).f_max))
    s_f = wind_spectrum(f[keep], u, cfg)  # per Hz
    amp = np.sqrt(2.0 * s_f * (grid.d_omega / (2.0 * np.pi))) * np.exp(1j * phases[:, keep])
    return u[:, None] + synthesise(amp, keep, grid)


def case_streams(
    seed: int, mooring_system: str, case_ids: npt.ArrayLike, n_bins: int, stream: str = "case"
) -> tuple[np.ndarray, np.ndarray]:
    """Wave and wind random phases of each case, from ``case_rng(seed, ms, case_id, stream)`` only.

    Parameters
    ----------
    seed : int
    mooring_system : str
    case_ids : array_like of int, shape (B,)
    n_bins : int
        Number of FFT bins (``n_fft // 2 + 1``).
    stream : str
        ``"case"`` or ``"bin"``: the dimension of the ids (see :func:`conventions.case_seed_sequence`).

    Returns
    -------
    wave_phase, wind_phase : numpy.ndarray, shape (B, n_bins)
        Uniform in ``[0, 2 pi)``; the wave phases are drawn first, then the wind phases.
    """
    ids = np.atleast_1d(np.asarray(case_ids))
    wave = np.empty((ids.size, n_bins))
    wind = np.empty((ids.size, n_bins))
    for b, cid in enumerate(ids):
        rng = case_rng(seed, mooring_system, int(cid), stream)
        wave[b] = rng.uniform(0.0, 2.0 * np.pi, n_bins)
        wind[b] = rng.uniform(0.0, 2.0 * np.pi, n_bins)
    return wave, wind
