"""Exact shortcuts of the BEM for a hull with dihedral symmetry (n rotations about z and the
mirror about the plane y = 0; OC4: n = 3), solved on Capytaine's dihedral mesh
(:func:`moorlife.hydro.capytaine_body` with ``mirror_symmetry``):

* :class:`DihedralLU`, the factorisation of Capytaine's dihedral influence matrix by its
  irreducible blocks: Capytaine factorises ``n`` blocks of ``2 m`` rows (``m`` panels in a
  ``2 n``-th of the hull), of which the blocks of the rotation frequencies ``k`` and ``n - k``
  are equal up to swapping their two halves, and the block ``k = 0`` splits into two of ``m``.
  Here one block of ``2 m`` per pair and two of ``m`` for ``k = 0`` (and ``k = n / 2``):
  ``10 m^3`` instead of ``24 m^3`` of work for ``n = 3``;
* :func:`heading_orbits` and :func:`transform_excitation` / :func:`transform_kochin`: the
  diffraction problem of heading ``g beta`` (``g`` in the group) is the one of ``beta`` moved
  by ``g``, so only headings in ``[0, pi / n]`` are solved (OC4, every 15 deg: 5 of 24).

Both are exact: on the dihedral mesh the discrete problem commutes with the group to
rounding, so they change the coefficients by rounding only (``tests/test_hydro.py``).
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sl


class DihedralLU:
    """LU factors of Capytaine's ``NestedBlockCirculantMatrix`` of ``2 n`` blocks ``(m, m)``.

    Capytaine's layout: the rows and columns run over the panel groups ``h0, m0, h1, m1, ...``
    (``h_i`` the reference half-wedge rotated ``i`` times, ``m_i`` its mirror image rotated
    ``i`` times); ``blocks[j]`` is the interaction of group ``j`` with ``h0``. Its rotation
    transform (the FFT over the ``n`` wedges, as Capytaine's block-circulant solve) has the
    blocks ``[[E_k, O_-k], [O_k, E_-k]]`` of ``2 m`` rows, ``E`` and ``O`` the FFTs of the even
    and odd blocks.
    """

    def __init__(self, matrix):
        blocks = np.asarray(matrix.blocks)
        self.n, self.m = blocks.shape[0] // 2, blocks.shape[1]
        n = self.n
        E = np.fft.fft(blocks[0::2], axis=0)
        O = np.fft.fft(blocks[1::2], axis=0)  # noqa: E741
        self.split = {}  # k -> LU of E_k + O_k and of E_k - O_k ([[P, Q], [Q, P]] blocks)
        self.full = {}  # k -> LU of the whole 2 m block
        for k in range(n // 2 + 1):
            if k == 0 or 2 * k == n:
                self.split[k] = (sl.lu_factor(E[k] + O[k]), sl.lu_factor(E[k] - O[k]))
            else:
                self.full[k] = sl.lu_factor(np.block([[E[k], O[-k]], [O[k], E[-k]]]))
        self.shape = (2 * n * self.m, 2 * n * self.m)

    def solve(self, b: np.ndarray) -> np.ndarray:
        n, m = self.n, self.m
        bh = np.fft.fft(b.reshape(n, 2, m), axis=0)
        xh = np.empty_like(bh)
        for k in range(n):
            kk = min(k, n - k)  # k > n / 2: the block of n - k with its halves swapped
            if kk in self.split:
                lu_p, lu_m = self.split[kk]
                s = sl.lu_solve(lu_p, bh[k, 0] + bh[k, 1])
                d = sl.lu_solve(lu_m, bh[k, 0] - bh[k, 1])
                xh[k, 0], xh[k, 1] = 0.5 * (s + d), 0.5 * (s - d)
            elif kk == k:
                xh[k] = sl.lu_solve(self.full[k], bh[k].reshape(-1)).reshape(2, m)
            else:
                xh[k] = sl.lu_solve(self.full[kk], bh[k, ::-1].reshape(-1)).reshape(2, m)[::-1]
        return np.fft.ifft(xh, axis=0).reshape(b.shape)


def dihedral_engine():
    """Capytaine's default engine, with :class:`DihedralLU` for a dihedral matrix.

    The engine keeps the last influence matrices, so a frequency's radiation and diffraction
    problems share one matrix; its factors are kept beside it here (Capytaine's own LU reuse
    for its matrices).
    """
    from capytaine.bem.engines import DefaultMatrixEngine
    from capytaine.tools.block_circulant_matrices import NestedBlockCirculantMatrix

    class DihedralEngine(DefaultMatrixEngine):
        _factored = (None, None)

        def linear_solver(self, A, b):
            if not (isinstance(A, NestedBlockCirculantMatrix) and A.nb_blocks >= 4 and np.ndim(A.blocks[0]) == 2):
                return super().linear_solver(A, b)
            if self._factored[0] is not A:
                self._factored = (A, DihedralLU(A))
            return self._factored[1].solve(b)

    return DihedralEngine()


def dihedral_order(body) -> int | None:
    """``n`` if the body's mesh (with its lid) is Capytaine's dihedral mesh of ``n`` rotations
    and the mirror about y = 0, 1 for the mirror alone, None otherwise."""
    from capytaine.meshes.symmetric_meshes import ReflectionSymmetricMesh, RotationSymmetricMesh

    mesh = body.mesh_including_lid
    if isinstance(mesh, RotationSymmetricMesh):
        w = mesh.wedge
        ok = isinstance(w, ReflectionSymmetricMesh) and w.plane == "xOz" and mesh.axis == "z+"
        return int(mesh.n) if ok else None
    if isinstance(mesh, ReflectionSymmetricMesh) and mesh.plane == "xOz":
        return 1
    return None


def _group(n: int):
    """The elements ``(alpha, s)`` of the dihedral group: the mirror ``y -> -y`` if ``s = -1``,
    then the rotation by ``alpha`` about z; an angle ``beta`` goes to ``alpha + s beta``."""
    return [(2.0 * np.pi * r / n, s) for s in (1, -1) for r in range(n)]


def heading_orbits(headings: np.ndarray, n: int, tol: float = 1e-9) -> tuple[np.ndarray, list[tuple[int, float, int]]]:
    """The headings to solve and how every heading follows from one of them.

    Returns ``solved`` (rad, each in ``[0, pi / n]``) and, per heading, ``(i, alpha, s)``: the
    heading is ``alpha + s solved[i]``.
    """
    solved: list[float] = []
    how = []
    for beta in np.asarray(headings, dtype=float):
        for alpha, s in _group(n):
            b0 = (s * (beta - alpha)) % (2.0 * np.pi)  # g^-1 beta
            if b0 > 2.0 * np.pi - tol:
                b0 = 0.0
            if b0 <= np.pi / n + tol:
                break
        match = [i for i, b in enumerate(solved) if abs(b - b0) < tol]
        if not match:
            solved.append(b0)
        how.append((match[0] if match else len(solved) - 1, alpha, s))
    return np.array(solved), how


def transform_excitation(F: np.ndarray, alpha: float, s: int) -> np.ndarray:
    """The generalised force ``(..., 6)`` (surge, sway, heave, roll, pitch, yaw about the
    origin) moved by the mirror ``y -> -y`` (if ``s = -1``: sway, roll and yaw change sign, the
    moments being axial vectors) and then the rotation by ``alpha`` about z."""
    F = np.array(F, dtype=complex)
    if s < 0:
        F[..., [1, 3, 5]] *= -1.0
    c, sn = np.cos(alpha), np.sin(alpha)
    out = F.copy()
    for i in (0, 3):  # (x, y) force, (x, y) moment
        out[..., i] = c * F[..., i] - sn * F[..., i + 1]
        out[..., i + 1] = sn * F[..., i] + c * F[..., i + 1]
    return out


def transform_kochin(H: np.ndarray, alpha: float, s: int) -> np.ndarray:
    """A Kochin function on ``nt + 1`` equally spaced directions ``[0, 2 pi]`` (the last equal to
    the first) moved by ``g = (alpha, s)``: ``H'(theta) = H(g^-1 theta) = H(s (theta - alpha))``.

    Raises
    ------
    ValueError
        If ``alpha`` is not a whole number of direction steps.
    """
    nt = H.shape[-1] - 1
    shift = alpha / (2.0 * np.pi / nt)
    if abs(shift - round(shift)) > 1e-9:
        raise ValueError(f"kochin directions: {nt} is not a multiple of the rotation order")
    j = (s * (np.arange(nt) - int(round(shift)))) % nt
    out = H[..., j]
    return np.concatenate([out, out[..., :1]], axis=-1)


def same_panels(body, *, rotation: bool):
    """The panels of a dihedral (or mirror-symmetric) body without its mirror symmetry: with the
    rotation alone (``rotation``, Capytaine's block-circulant solve of ``n`` wedges) or with no
    symmetry. The references of the exactness checks (tests, ``benchmarks/bench_bem.py``).

    Capytaine takes a panel's radius (where its near-field integration starts) as the distance
    from the centre to the panel's first corner, and its mirror image reverses the corners; the
    mirrored panels are given the mirror of the first corner first, as the dihedral solve,
    which integrates over the reference half only, sees them (otherwise the two solves differ
    by up to 2e-4 of the peak through that switch alone).
    """
    import capytaine as cpt

    def unmirrored(mesh):
        mirror = mesh.wedge if hasattr(mesh, "wedge") else mesh  # dihedral, or the mirror alone
        other = mirror.other_half
        rolled = cpt.Mesh(other.vertices, [list(f[-1:]) + list(f[:-1]) for f in other._faces], auto_clean=False)
        half = cpt.Mesh.join_meshes(mirror.half, rolled)
        if not hasattr(mesh, "wedge"):
            return half
        if rotation:
            return cpt.RotationSymmetricMesh(half, n=mesh.n)
        return cpt.Mesh.join_meshes(*[half.rotated_z(2.0 * np.pi * i / mesh.n) for i in range(mesh.n)])

    return cpt.FloatingBody(
        mesh=unmirrored(body.mesh),
        lid_mesh=None if body.lid_mesh is None else unmirrored(body.lid_mesh),
        dofs=cpt.rigid_body_dofs(rotation_center=(0.0, 0.0, 0.0)),
        center_of_mass=(0.0, 0.0, 0.0),
        name=body.name,
    )
