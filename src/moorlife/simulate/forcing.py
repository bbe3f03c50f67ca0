"""External forcing of a batch on the integration grid: wave forces, drag kinematics, wind."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.fft

from moorlife import environment as env
from moorlife.simulate.model import ModelInputs

__all__ = ["Forcing", "build_forcing", "forcing_from"]


@dataclass(frozen=True)
class Forcing:
    """External forcing of a batch, sampled on the integration grid.

    Attributes
    ----------
    grid : environment.RecordGrid
    force : (B, n + 1, 6)
        First-order plus slow-drift wave force at ``t_j = j dt``, N and N m.
    wind : (B, n + 1)
        Hub-height wind speed, m/s (zero: no wind).
    wind_dir : (B, 2)
        Unit vector of the wind's direction of travel (x, y).
    kin_every : int
        Kinematics are sampled every ``kin_every`` steps.
    kinematics : (B, nk, 3, ns) float32
        Undisturbed wave particle velocity at the strips' mean positions, m/s.
    """

    grid: env.RecordGrid
    force: np.ndarray
    wind: np.ndarray
    wind_dir: np.ndarray
    kin_every: int
    kinematics: np.ndarray


def _interp_heading(table: np.ndarray, headings: np.ndarray, theta: float) -> np.ndarray:
    """Linear interpolation of ``table (nw, nh, 6)`` at propagation angle ``theta`` on the circle."""
    from moorlife.hydro import interp_heading

    if headings.size == 1:
        return table[:, 0, :]
    return interp_heading(headings, table, float(theta))


def _interp_omega(values: np.ndarray, omega: np.ndarray, target: np.ndarray) -> np.ndarray:
    """Interpolate ``values (nw, 6)`` (complex or real) to ``target`` rad/s; zero outside."""
    out = np.zeros((target.size, values.shape[1]), dtype=values.dtype)
    for d in range(values.shape[1]):
        if np.iscomplexobj(values):
            out[:, d] = np.interp(target, omega, values[:, d].real, left=0, right=0) + 1j * np.interp(
                target, omega, values[:, d].imag, left=0, right=0
            )
        else:
            out[:, d] = np.interp(target, omega, values[:, d], left=0, right=0)
    return out


_KIN_CHUNK = 24  # kinematic series synthesised per FFT call


def _drag_kinematics_tf(model: ModelInputs, k: np.ndarray, omega: np.ndarray, theta: float) -> np.ndarray:
    """Velocity transfer functions at the strips, ``(nk, ns, 3)`` complex, per metre of amplitude."""
    p = model.strip_pos
    h = model.depth
    c, s = math.cos(theta), math.sin(theta)
    phase = np.exp(1j * k[:, None] * (p[None, :, 0] * c + p[None, :, 1] * s))
    z = np.minimum(p[None, :, 2], 0.0)
    kh = np.minimum(k[:, None] * h, 350.0)
    kz = np.minimum(k[:, None] * (z + h), 350.0)
    horiz = omega[:, None] * np.cosh(kz) / np.sinh(kh) * phase
    vert = -1j * omega[:, None] * np.sinh(kz) / np.sinh(kh) * phase
    wet = p[None, :, 2] <= 0.0
    horiz = horiz * wet
    vert = vert * wet
    return np.stack([horiz * c, horiz * s, vert], axis=-1)


def build_forcing(
    model: ModelInputs,
    grid: env.RecordGrid,
    waves: env.WaveComponents,
    wind: np.ndarray,
    wind_dir_deg: np.ndarray,
    *,
    kin_every: int,
    second_order: bool = True,
) -> Forcing:
    """Wave forces, wave kinematics and wind of a batch on the integration grid.

    Parameters
    ----------
    model : ModelInputs
    grid : environment.RecordGrid
    waves : environment.WaveComponents
        Complex amplitudes ``(B, nk)`` and propagation angles ``(B,)``.
    wind : (B, n + 1)
        Hub wind speed series, m/s.
    wind_dir_deg : (B,)
        Nautical direction the wind comes from, deg.
    kin_every : int
        Sampling of the drag kinematics, in steps.
    second_order : bool
        Add Newman's slow drift (difference-frequency part ``|a|^2`` of the drift envelope).

    Returns
    -------
    Forcing
    """
    from moorlife.conventions import flow_vector

    nb = waves.amplitude.shape[0]
    n1 = grid.n_steps + 1
    force = np.empty((nb, n1, 6))
    k = env.wave_number(waves.omega, model.depth)
    nkin = (grid.n_steps // kin_every) + 2
    ns = model.strip_pos.shape[0]
    kin = np.zeros((nb, nkin, 3, ns), dtype=np.float32)
    for b in range(nb):
        theta = float(waves.theta[b])
        x = _interp_omega(_interp_heading(model.excitation, model.headings, theta), model.omega, waves.omega)
        coeff = waves.amplitude[b][None, :] * x.T  # (6, nk)
        force[b] = env.synthesise(coeff, waves.index, grid).T
        if second_order:
            d = _interp_omega(_interp_heading(model.drift, model.headings, theta), model.omega, waves.omega)
            for dof in range(6):
                for sign in (1.0, -1.0):
                    part = np.maximum(sign * d[:, dof], 0.0)
                    if not part.any():
                        continue
                    a = env.synthesise_complex((np.sqrt(part) * waves.amplitude[b])[None, :], waves.index, grid)[0]
                    force[b, :, dof] += sign * (a.real**2 + a.imag**2)
        if ns:
            tf = _drag_kinematics_tf(model, k, waves.omega, theta)  # (nk, ns, 3)
            coeff = (waves.amplitude[b][:, None, None] * tf).transpose(0, 2, 1).reshape(waves.omega.size, 3 * ns).T
            flat = kin[b].reshape(nkin, ns * 3)
            # synthesise directly on the coarse kinematics grid (same frequency bins)
            coarse = grid.n_fft % kin_every == 0 and 2 * waves.index.max() < grid.n_fft // kin_every
            n_c = grid.n_fft // kin_every if coarse else grid.n_fft
            idx = (np.arange(nkin) * (1 if coarse else kin_every)) % n_c  # periodic synthesis
            for c0 in range(0, ns * 3, _KIN_CHUNK):  # bounded temporaries
                c1 = min(c0 + _KIN_CHUNK, ns * 3)
                spec = np.zeros((c1 - c0, n_c // 2 + 1), dtype=complex)
                spec[:, waves.index] = np.conj(coeff[c0:c1]) * (n_c / 2.0)
                series = scipy.fft.irfft(spec, n=n_c, axis=-1)
                flat[:, c0:c1] = series[:, idx].T
    wdir = flow_vector(np.asarray(wind_dir_deg, dtype=float)).reshape(nb, 2)
    return Forcing(
        grid=grid,
        force=force,
        wind=np.asarray(wind, dtype=float),
        wind_dir=wdir,
        kin_every=int(kin_every),
        kinematics=kin,
    )


def forcing_from(forcing: Forcing, step: int) -> Forcing:
    """The same forcing from step ``step`` on, as the forcing of a record that starts there.

    Sample ``j`` of the result is sample ``step + j`` of ``forcing``: the wave and wind
    realisation is unchanged, only the time origin moves. With it, records started at different
    times (different transients) see the same waves and wind over the same kept window, for
    paired comparisons (``validation/transient.py``). The grid keeps its FFT length and
    frequency step (those of the synthesis).

    Parameters
    ----------
    forcing : Forcing
    step : int
        First step kept, ``0 <= step < n_steps``, a multiple of ``kin_every``.

    Returns
    -------
    Forcing
    """
    grid = forcing.grid
    step = int(step)
    if not 0 <= step < grid.n_steps or step % forcing.kin_every:
        raise ValueError(
            f"forcing_from: step {step} must be in [0, {grid.n_steps}) and a multiple of kin_every = {forcing.kin_every}"
        )
    k = step // forcing.kin_every
    return Forcing(
        grid=env.RecordGrid(dt=grid.dt, n_steps=grid.n_steps - step, n_fft=grid.n_fft, d_omega=grid.d_omega),
        force=np.ascontiguousarray(forcing.force[:, step:]),
        wind=np.ascontiguousarray(forcing.wind[:, step:]),
        wind_dir=forcing.wind_dir,
        kin_every=forcing.kin_every,
        kinematics=np.ascontiguousarray(forcing.kinematics[:, k:]),
    )
