"""Platform hydrodynamics: hull mesh, BEM (Capytaine), and the simulator's linear model.

Conventions (the package's, used everywhere in moorlife):

* Frame: origin at the still-water line on the platform centreline, x east, y north, z up;
  degrees of freedom ``surge, sway, heave, roll, pitch, yaw`` about the origin.
* Headings are *propagation* angles in radians, counter-clockwise from ``+x`` (the direction
  the waves travel to), see :func:`moorlife.conventions.propagation_angle`.
* **Phase convention: WAMIT's** ``exp(+i omega t)``. A wave component of amplitude ``a`` and
  phase ``phi`` has elevation ``eta(t) = Re[a exp(i(omega t + phi))] = a cos(omega t + phi)``
  at the origin, and exerts ``F(t) = Re[X a exp(i(omega t + phi))]`` with ``X`` the excitation
  per unit amplitude stored here. Capytaine solves with ``exp(-i omega t)``; its complex
  excitation is conjugated once, in :func:`run_bem`. WAMIT files are read as they are.
* Hydrostatic stiffness in ``platform.nc`` is buoyancy + waterplane only (as WAMIT ``.hst``);
  the gravity terms ``-m g z_G`` of the whole system are added in :func:`load_platform_model`.
* Mean drift coefficients ``drift[omega, heading, dof]`` are the mean force per wave
  amplitude squared (N/m^2, N m/m^2): a regular wave ``a cos(omega t)`` gives the mean force
  ``a^2 drift``.

The Capytaine part (:func:`run_bem`) is the only non-pure function; every kernel below it is
numpy in, numpy out.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt
import xarray as xr

from moorlife.names import DOFS

__all__ = [
    # geometry and mesh
    "Member",
    "members_from_config",
    "n_around",
    "wall_panels",
    "annulus_panels",
    "brace_extent",
    "hull_panels",
    "lid_panels",
    "capytaine_body",
    # BEM
    "frequency_grid",
    "heading_grid",
    "run_bem",
    "bem_from_settings",
    "richardson",
    "bem_settings",
    "wavenumber",
    "far_field_drift",
    "platform_dataset",
    # rigid body and hydrostatics
    "rigid_body_mass_matrix",
    "system_mass_properties",
    "gravity_stiffness",
    "motion_rao",
    "natural_periods",
    # radiation
    "retardation_kernel",
    "added_mass_infinite_ogilvie",
    "fit_state_space",
    "StateSpace",
    "state_space_kernel",
    "state_space_response",
    # excitation, drift, drag
    "interp_heading",
    "excitation_at",
    "drift_at",
    "newman_drift_force",
    "morison_elements",
    "point_velocity",
    "morison_drag_force",
    "generalised_force",
    # the simulator's model
    "PlatformModel",
    "load_platform_model",
]

log = logging.getLogger(__name__)

DOF_NAMES: tuple[str, ...] = DOFS
RADIATING_DOF = "radiating_dof"


# ------------------------------------------------------------------ geometry and mesh


@dataclass(frozen=True)
class Member:
    """One cylindrical member of the hull.

    Attributes
    ----------
    name : str
    kind : str
        ``"column"`` (vertical, meshed with caps) or ``"brace"`` (tube joined to the columns it ends on).
    a, b : numpy.ndarray
        End points ``(3,)`` in m; for a column ``a`` is the bottom.
    diameter : float
        Outer diameter in m.
    cd : float
        Transverse (Morison) drag coefficient.
    axial_cd : float
        Axial drag coefficient applied over ``pi D^2 / 4`` at end ``a`` (heave plate); 0 if none.
    """

    name: str
    kind: str
    a: np.ndarray
    b: np.ndarray
    diameter: float
    cd: float
    axial_cd: float = 0.0

    @property
    def radius(self) -> float:
        return 0.5 * self.diameter

    @property
    def length(self) -> float:
        return float(np.linalg.norm(self.b - self.a))

    @property
    def axis(self) -> np.ndarray:
        return (self.b - self.a) / self.length


def members_from_config(platform_cfg: dict, source: str = "platform.yaml") -> list[Member]:
    """Build the member list from the ``members`` block of ``platform.yaml``.

    Raises
    ------
    ValueError
        Naming the file, the member and the field, on a missing or invalid value.
    """
    raw = platform_cfg.get("members")
    if not raw:
        raise ValueError(f"{source}: 'members' is missing or empty")
    out = []
    for i, m in enumerate(raw):
        where = f"{source}: members[{i}] ({m.get('name', '?')})"
        for key in ("name", "kind", "a", "b", "diameter", "cd"):
            if key not in m:
                raise ValueError(f"{where}: field '{key}' is missing")
        if m["kind"] not in ("column", "brace"):
            raise ValueError(f"{where}: kind = {m['kind']!r}, expected 'column' or 'brace'")
        a = np.asarray(m["a"], dtype=float)
        b = np.asarray(m["b"], dtype=float)
        if a.shape != (3,) or b.shape != (3,) or not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
            raise ValueError(f"{where}: 'a' and 'b' must be 3 finite numbers, got {m['a']!r}, {m['b']!r}")
        if np.linalg.norm(b - a) <= 0:
            raise ValueError(f"{where}: a == b, the member has zero length")
        d = float(m["diameter"])
        if not d > 0:
            raise ValueError(f"{where}: diameter = {m['diameter']!r} must be > 0")
        cd = float(m["cd"])
        axcd = float(m.get("axial_cd", 0.0))
        if cd < 0 or axcd < 0:
            raise ValueError(f"{where}: drag coefficients must be >= 0, got cd={cd}, axial_cd={axcd}")
        if m["kind"] == "column":
            if not np.allclose(a[:2], b[:2]) or b[2] <= a[2]:
                raise ValueError(f"{where}: a column must be vertical with a below b, got a={a.tolist()}, b={b.tolist()}")
        out.append(Member(str(m["name"]), str(m["kind"]), a, b, d, cd, axcd))
    return out


def n_around(radius: float, panel_size: float, minimum: int = 8) -> int:
    """Number of panels around a circle of ``radius`` for a target panel size (even, >= minimum)."""
    n = max(minimum, int(np.ceil(2.0 * np.pi * radius / panel_size)))
    return n + (n % 2)


def _equal_area_radius(radius: float, n: int) -> float:
    # a regular n-gon of circumradius rho has area n rho^2 sin(2 pi / n) / 2
    return radius * np.sqrt(2.0 * np.pi / (n * np.sin(2.0 * np.pi / n)))


def _basis(e: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    t = np.array([1.0, 0.0, 0.0]) if abs(e[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    if abs(e[2]) > 0.99:  # vertical: start the angle on +x so columns share orientation
        u = np.array([1.0, 0.0, 0.0])
    else:
        u = np.cross(e, t)
        u /= np.linalg.norm(u)
    v = np.cross(e, u)
    return u, v


def wall_panels(a: np.ndarray, b: np.ndarray, radius: float, panel_size: float, n_theta: int | None = None):
    """Quadrilateral panels of a cylinder wall from ``a`` to ``b`` (outward normals).

    Returns
    -------
    vertices : numpy.ndarray
        ``(nv, 3)`` in m.
    faces : numpy.ndarray
        ``(nf, 4)`` vertex indices.
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    length = float(np.linalg.norm(b - a))
    e = (b - a) / length
    nt = n_theta or n_around(radius, panel_size)
    nz = max(1, int(np.ceil(length / panel_size)))
    rho = _equal_area_radius(radius, nt)
    u, v = _basis(e)
    th = np.linspace(0.0, 2.0 * np.pi, nt + 1)[:-1]
    s = np.linspace(0.0, length, nz + 1)
    ring = rho * (np.cos(th)[:, None] * u + np.sin(th)[:, None] * v)
    vertices = (a + s[:, None, None] * e + ring[None, :, :]).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(nz), np.arange(nt), indexing="ij")
    i, j = i.ravel(), j.ravel()
    jn = (j + 1) % nt
    # e_theta x e_s = +e_r (outward) for the order (j, s), (j+1, s), (j+1, s+1), (j, s+1)
    faces = np.stack([i * nt + j, i * nt + jn, (i + 1) * nt + jn, (i + 1) * nt + j], axis=1)
    return vertices, faces


def annulus_panels(centre, r_inner: float, r_outer: float, panel_size: float, normal_up: bool,
                   n_theta: int | None = None):
    """Panels of a horizontal disk (``r_inner = 0``) or annulus at ``centre``.

    Returns ``(vertices (nv, 3), faces (nf, 4))``; triangles repeat their last vertex.
    The normal is ``+z`` if ``normal_up`` else ``-z``.
    """
    c = np.asarray(centre, dtype=float)
    nt = n_theta or n_around(r_outer, panel_size)
    r_out = _equal_area_radius(r_outer, nt)
    # both rings carry nt corners at their own equal-area radius: the annulus has the exact
    # area pi (r_outer^2 - r_inner^2) (the inner ring of nt corners sits within 1 % of r_inner
    # of the narrower column's own polygon)
    r_in = _equal_area_radius(r_inner, nt) if r_inner > 0 else 0.0
    nr = max(1, int(np.ceil((r_out - r_in) / panel_size)))
    radii = np.linspace(r_in, r_out, nr + 1)
    th = np.linspace(0.0, 2.0 * np.pi, nt + 1)[:-1]
    if r_in == 0.0:
        radii = radii[1:]
    ring = np.stack([np.cos(th), np.sin(th), np.zeros_like(th)], axis=1)
    vertices = (c + radii[:, None, None] * ring[None, :, :]).reshape(-1, 3)
    faces = []
    for i in range(len(radii) - 1):
        for j in range(nt):
            jn = (j + 1) % nt
            # r-hat x theta-hat = +z for (inner j, outer j, outer j+1, inner j+1)
            faces.append([i * nt + j, (i + 1) * nt + j, (i + 1) * nt + jn, i * nt + jn])
    if r_in == 0.0:
        ic = len(vertices)
        vertices = np.vstack([vertices, c[None, :]])
        for j in range(nt):
            faces.append([ic, j, (j + 1) % nt, (j + 1) % nt])
    faces = np.asarray(faces, dtype=int)
    if not normal_up:
        faces = faces[:, ::-1]
    return vertices, faces


def _clip_polygon_below(poly: list[np.ndarray], z: float) -> list[np.ndarray]:
    """The part of a planar polygon (list of ``(3,)`` corners) with ``z <= z``
    (Sutherland-Hodgman against one plane)."""
    out = []
    for p, q in zip(poly, poly[1:] + poly[:1]):
        p_in, q_in = p[2] <= z, q[2] <= z
        if p_in:
            out.append(p)
        if p_in != q_in:
            out.append(p + (z - p[2]) / (q[2] - p[2]) * (q - p))
    return out


def _clip_below(vertices: np.ndarray, faces: np.ndarray, z: float = 0.0):
    """Keep the part of every panel below ``z``.

    Panels entirely above are dropped; panels across ``z`` are cut along it (a cut quad is a
    triangle, a quad, or a pentagon stored as a quad and a triangle), so an inclined brace
    gets its exact elliptical waterline. Unused vertices are removed.
    """
    zf = vertices[faces, 2]
    below = np.all(zf <= z + 1e-9, axis=1)
    across = ~below & np.any(zf < z - 1e-9, axis=1)
    verts, new = [vertices], [faces[below]]
    n = len(vertices)
    for face in faces[across]:
        corners = list(dict.fromkeys(face.tolist()))  # a triangle repeats its last vertex
        poly = _clip_polygon_below([vertices[k] for k in corners], z)
        pieces = [[0, 1, 2, 3 if len(poly) > 3 else 2]] + ([[0, 3, 4, 4]] if len(poly) == 5 else [])
        verts.append(np.asarray(poly))
        new.append(n + np.asarray(pieces))
        n += len(poly)
    vertices, faces = np.vstack(verts), np.vstack(new)
    used, faces = np.unique(faces, return_inverse=True)
    return vertices[used], faces.reshape(-1, 4)


def _concat(parts):
    verts, faces, off = [], [], 0
    for v, f in parts:
        verts.append(v)
        faces.append(f + off)
        off += len(v)
    return np.vstack(verts), np.vstack(faces)


#: Minimum number of panels around a brace. A 1.6 m OC4 brace with 1.2 m panels would
#: otherwise be a hexagon; 12 lowered the surge added mass by 0.8 % (towards WAMIT) at the
#: default panel size, for 15 % more panels (validation/hydro.md).
BRACE_PANELS_AROUND = 12


def _inside_cylinder(points: np.ndarray, a: np.ndarray, b: np.ndarray, radius: float,
                     tol: float = 1e-6) -> np.ndarray:
    """``(n,)`` True where ``points (n, 3)`` lie strictly inside the solid cylinder ``a -> b``."""
    length = float(np.linalg.norm(b - a))
    e = (b - a) / length
    s = (points - a) @ e
    d = np.linalg.norm(points - a - s[:, None] * e, axis=1)
    return (d < radius - tol) & (s > tol) & (s < length - tol)


def _drop_covered(vertices: np.ndarray, faces: np.ndarray,
                  solids: Sequence[tuple[np.ndarray, np.ndarray, float, float]]) -> np.ndarray:
    """``faces`` without the panels another member covers.

    ``solids`` holds cylinders ``(a, b, radius, margin)``. A panel is covered when its centre
    is inside one of them and every corner is inside the same one grown by ``margin`` (the
    smaller member's radius). The corner condition keeps panels much larger than the junction
    (coarse meshes): removing them would open a hole into the body, keeping them only leaves
    an overlap.
    """
    centres = vertices[faces].mean(axis=1)
    covered = np.zeros(len(faces), dtype=bool)
    for a, b, radius, margin in solids:
        covered |= (_inside_cylinder(centres, a, b, radius)
                    & _inside_cylinder(vertices, a, b, radius + margin)[faces].all(axis=1))
    return faces[~covered]


def brace_extent(brace: Member, columns: Sequence[Member]) -> tuple[np.ndarray, np.ndarray, bool, bool]:
    """End points of a brace as meshed, and whether each end is closed by a column.

    An end that lies inside a column or on its wall (HydroDyn joints end on the wall) is
    pushed one column radius further along the brace axis, into the column, so that the
    brace and the column overlap; :func:`hull_panels` then removes the panels of each that lie
    inside the other (the union of the two solids). An end in open water is kept and gets a
    cap.

    Returns
    -------
    a, b : numpy.ndarray
        ``(3,)`` meshed end points, m.
    closed_a, closed_b : bool
        True where the end is inside a column.

    Raises
    ------
    ValueError
        Naming the brace and the column, if the pushed end leaves the column under water (a
        brace that grazes a column, or a column shorter than the push).
    """
    e = brace.axis
    out = []
    for end, sign in ((brace.a, -1.0), (brace.b, 1.0)):
        host = [c for c in columns if _inside_cylinder(end[None, :], c.a, c.b, c.radius, tol=-1e-3 * c.radius)[0]]
        if host:
            c = max(host, key=lambda c: c.radius)
            pushed = end + sign * c.radius * e
            if pushed[2] < 0.0 and not _inside_cylinder(pushed[None, :], c.a, c.b, c.radius)[0]:  # above: clipped
                raise ValueError(
                    f"brace {brace.name!r}: its end {end.round(3).tolist()} on column {c.name!r}, pushed "
                    f"{c.radius:g} m into the column along the brace, leaves it at "
                    f"{pushed.round(3).tolist()}: the mesher joins braces that enter a column "
                    "steeply enough to stay inside it for one column radius"
                )
            out.append((pushed, True))
        else:
            out.append((end, False))
    (a, closed_a), (b, closed_b) = out
    return a, b, closed_a, closed_b


def _disk_panels(centre: np.ndarray, normal: np.ndarray, radius: float, panel_size: float, n_theta: int):
    """A disk of ``radius`` at ``centre`` facing ``normal``, as ``(vertices, faces)``."""
    u, v = _basis(normal)
    verts, faces = annulus_panels([0.0, 0.0, 0.0], 0.0, radius, panel_size, True, n_theta)
    basis = np.stack([u, v, normal])  # local (x, y, z) -> (u, v, n): right-handed, keeps +z -> +n
    return centre + verts @ basis, faces


def hull_panels(members: Sequence[Member], panel_size: float, around: float = 1.0):
    """Panels of the wetted hull (below z = 0) of a platform.

    Columns are closed by their end caps (an annulus where a narrower coaxial column
    continues). Braces are tubes pushed into the columns they end on (:func:`brace_extent`);
    the panels of a brace inside a column and those of a column inside a brace are removed,
    so that the mesh is the outer surface of the union of the members, with no enclosed
    fluid and no surface inside the body. A brace end in open water is capped.

    Parameters
    ----------
    members : sequence of Member
    panel_size : float
        Target panel edge length in m.
    around : float
        Circumferential refinement: every member gets ``around`` times as many panels around
        as ``panel_size`` gives (panels ``panel_size / around`` wide, ``panel_size`` long).
        The surge added mass converges with the number of panels around, not along
        (``validation/hydro.md``, section 0b).

    Returns
    -------
    vertices : numpy.ndarray ``(nv, 3)``, faces : numpy.ndarray ``(nf, 4)``
    """
    if not panel_size > 0:
        raise ValueError(f"panel_size must be > 0, got {panel_size!r}")
    if not around > 0:
        raise ValueError(f"around must be > 0, got {around!r}")
    cols = [m for m in members if m.kind == "column"]
    braces = [(m, *brace_extent(m, cols)) for m in members if m.kind == "brace" and min(m.a[2], m.b[2]) < 0.0]
    parts = []
    brace_solids = [(a, b, br.radius, br.radius) for br, a, b, _, _ in braces]
    for m in cols:
        if m.a[2] >= 0.0:
            continue
        top = min(m.b[2], 0.0)
        nt = n_around(m.radius, panel_size / around)
        col_parts = [wall_panels(m.a, np.array([m.a[0], m.a[1], top]), m.radius, panel_size, nt)]
        for end, up in ((m.a, False), (m.b, True)):
            if end[2] >= 0.0:
                continue
            # coaxial column continuing from this end on the other side
            others = [o for o in cols if o is not m and np.allclose(o.a[:2], m.a[:2])
                      and np.isclose((o.a if up else o.b)[2], end[2])]
            r_cover = max((o.radius for o in others), default=0.0)
            if r_cover >= m.radius:
                continue
            col_parts.append(annulus_panels(end, r_cover, m.radius, panel_size, up, nt))
        parts += [(v, _drop_covered(v, f, brace_solids)) for v, f in col_parts]
    for m, a, b, closed_a, closed_b in braces:
        nt = n_around(m.radius, panel_size / around, minimum=BRACE_PANELS_AROUND)
        caps = [_disk_panels(p, s * m.axis, m.radius, panel_size, nt)
                for p, s, closed in ((a, -1.0, closed_a), (b, 1.0, closed_b)) if not closed and p[2] < 0.0]
        column_solids = [(col.a, col.b, col.radius, m.radius) for col in cols]
        parts += [_clip_below(v, _drop_covered(v, f, column_solids))
                  for v, f in [wall_panels(a, b, m.radius, panel_size, nt), *caps]]
    if not parts:
        raise ValueError("no member is below the still-water line: nothing to mesh")
    return _concat(parts)


def lid_panels(members: Sequence[Member], panel_size: float, z: float = 0.0, around: float = 1.0):
    """Panels of the interior free surface (lid) of every column crossing the water line.

    ``around`` as in :func:`hull_panels`, so that the lid rim matches the column polygon.

    Used for irregular-frequency removal. Braces are not lidded (their waterplane is < 2 %).
    Returns ``(vertices (nv, 3), faces (nf, 4))`` with normals pointing down (into the body).
    """
    parts = [
        annulus_panels([m.a[0], m.a[1], z], 0.0, m.radius, panel_size, False,
                       n_around(m.radius, panel_size / around))
        for m in members
        if m.kind == "column" and m.a[2] < z < m.b[2]
    ]
    if not parts:
        raise ValueError("no column crosses the water line: no lid to build")
    return _concat(parts)


def _to_mesh(vertices, faces, name):
    from capytaine import Mesh

    faces_list = [list(f[:3]) if f[2] == f[3] else list(f) for f in faces]
    return Mesh(vertices, faces_list, name=name)


def capytaine_body(
    members: Sequence[Member],
    panel_size: float,
    *,
    rotational_symmetry: int | None = None,
    lid: bool = True,
    around: float = 1.0,
):
    """The wetted hull as a ``capytaine.FloatingBody`` with six rigid-body dofs about the origin.

    Parameters
    ----------
    members : sequence of Member
    panel_size : float
        Target panel size in m.
    rotational_symmetry : int or None
        ``n`` to solve with an n-fold symmetry about the z axis (3 for OC4: about 3x faster).
        The hull is meshed whole, one wedge is cut out and rotated; a hull that is not
        n-fold symmetric is refused.
    lid : bool
        Add an interior free-surface lid (irregular-frequency removal).
    around : float
        Circumferential refinement (:func:`hull_panels`).

    Raises
    ------
    ValueError
        If ``rotational_symmetry`` is requested for a hull that does not have it.
    """
    import capytaine as cpt

    hull = _to_mesh(*hull_panels(members, panel_size, around), name="hull")
    lid_mesh = _to_mesh(*lid_panels(members, panel_size, around=around), name="lid") if lid else None
    if rotational_symmetry:
        n = int(rotational_symmetry)
        sym = cpt.RotationSymmetricMesh(hull.extract_wedge(n), n=n, name="hull")
        ref = _mesh_moments(hull)
        got = _mesh_moments(sym)
        if not np.allclose(got, ref, rtol=0.0, atol=0.01 * abs(ref[0])):
            raise ValueError(
                f"hydro.mesh.rotational_symmetry = {n}: the hull is not {n}-fold symmetric about z "
                f"(volume/first moments {ref.round(1).tolist()} whole vs {got.round(1).tolist()} "
                "rebuilt from one wedge); set it to null"
            )
        hull = sym
        if lid_mesh is not None:
            lid_mesh = cpt.RotationSymmetricMesh(lid_mesh.extract_wedge(n), n=n, name="lid")
    return cpt.FloatingBody(
        mesh=hull,
        lid_mesh=lid_mesh,
        dofs=cpt.rigid_body_dofs(rotation_center=(0.0, 0.0, 0.0)),
        center_of_mass=(0.0, 0.0, 0.0),
        name="platform",
    )


def _mesh_moments(mesh) -> np.ndarray:
    # volume (from x n_x) and the first moments of area of the panels: a symmetry fingerprint
    n, c, a = mesh.faces_normals, mesh.faces_centers, mesh.faces_areas
    return np.array([np.sum(c[:, 0] * n[:, 0] * a), np.sum(c[:, 0] * a), np.sum(c[:, 1] * a), np.sum(a)])


# ---------------------------------------------------------------------------- BEM

def frequency_grid(omega_min: float, omega_max: float, n: int) -> np.ndarray:
    """Equally spaced angular frequencies ``(n,)`` in rad/s.

    Raises
    ------
    ValueError
        Unless ``0 < omega_min < omega_max`` and ``n >= 2``.
    """
    if not (0.0 < omega_min < omega_max) or int(n) < 2:
        raise ValueError(f"hydro.omega: need 0 < min < max and n >= 2, got min={omega_min}, max={omega_max}, n={n}")
    return np.linspace(float(omega_min), float(omega_max), int(n))


def heading_grid(step_deg: float) -> np.ndarray:
    """Propagation headings ``[0, 360)`` deg every ``step_deg``, returned in radians."""
    step = float(step_deg)
    if not (0.0 < step <= 180.0) or abs(360.0 / step - round(360.0 / step)) > 1e-9:
        raise ValueError(f"hydro.heading_step: {step_deg!r} must divide 360 and lie in (0, 180]")
    return np.deg2rad(np.arange(0.0, 360.0 - 1e-9, step))


def wavenumber(omega: npt.ArrayLike, depth: float, g: float) -> np.ndarray:
    """Finite-depth wavenumber from ``omega^2 = g k tanh(k h)`` (Newton, rad/m)."""
    w = np.asarray(omega, dtype=float)
    k0 = w**2 / g
    k = np.where(k0 * depth > 20, k0, np.maximum(k0, w / np.sqrt(g * depth)))
    for _ in range(60):
        th = np.tanh(k * depth)
        f = g * k * th - w**2
        df = g * th + g * k * depth * (1.0 - th**2)
        k = k - f / df
    return k


def bem_settings(hydro_cfg: Mapping, platform_cfg: Mapping) -> dict:
    """Everything that changes the BEM result, as plain data (the ``hydro`` rule's params).

    Geometry and environment come from ``platform.yaml``; grid, headings and mesh from the
    ``hydro`` section of the study config. Mass properties and the linear mooring stiffness
    are included because the mean drift coefficients depend on the body motions. For
    ``source: wamit`` only the file prefix and the environment matter.
    """
    if hydro_cfg["source"] == "wamit":  # only the files (rule inputs) and the redimensionalisation
        return {"source": "wamit", "wamit_prefix": hydro_cfg.get("wamit_prefix"),
                "environment": dict(platform_cfg["environment"])}
    res = hydro_cfg["mesh"]["resolution"]
    sizes = hydro_cfg["mesh"]["panel_size"]
    if res not in sizes:
        raise ValueError(f"hydro.mesh.resolution = {res!r} is not one of hydro.mesh.panel_size {sorted(sizes)}")
    around = float(hydro_cfg["mesh"].get("around_refinement", 1.0))
    # omitted at its default 1.0: the mesh is then the one from before the option existed, and
    # the settings (the rule's params) of existing runs stay valid, so no BEM reruns for nothing
    extra = {"around_refinement": around} if around != 1.0 else {}
    return {
        "source": hydro_cfg["source"],
        "wamit_prefix": hydro_cfg.get("wamit_prefix"),
        "environment": dict(platform_cfg["environment"]),
        "members": [dict(m) for m in platform_cfg["members"]],
        "omega": dict(hydro_cfg["omega"]),
        "heading_step": float(hydro_cfg["heading_step"]),
        "panel_size": float(sizes[res]),
        "richardson": bool(hydro_cfg["mesh"].get("richardson", False)),
        "rotational_symmetry": hydro_cfg["mesh"].get("rotational_symmetry"),
        "irregular_frequency_removal": bool(hydro_cfg["irregular_frequency_removal"]),
        "kochin_directions": int(hydro_cfg["kochin_directions"]),
        "bodies": {k: dict(platform_cfg[k]) for k in ("platform", "tower", "rna")},
        "mooring_stiffness_diag": list(platform_cfg.get("mooring_stiffness_diag", [0.0] * 6)),
        **extra,
    }


def run_bem(
    body,
    omega: np.ndarray,
    headings: np.ndarray,
    *,
    water_depth: float,
    rho: float,
    g: float,
    mass_matrix: np.ndarray,
    stiffness: np.ndarray,
    n_kochin: int = 72,
    n_jobs: int = 1,
) -> xr.Dataset:
    """Solve radiation and diffraction with Capytaine and build the ``platform.nc`` dataset.

    Parameters
    ----------
    body : capytaine.FloatingBody
        From :func:`capytaine_body`.
    omega : numpy.ndarray
        ``(nw,)`` rad/s.
    headings : numpy.ndarray
        ``(nh,)`` propagation angles, rad.
    water_depth, rho, g : float
        m, kg/m^3, m/s^2.
    mass_matrix : numpy.ndarray
        ``(6, 6)`` system mass about the origin, used only for the motions behind the drift.
    stiffness : numpy.ndarray
        ``(6, 6)`` total restoring (hydrostatic + gravity + linear mooring) for the same.
    n_kochin : int
        Number of directions of the Kochin functions (far-field mean drift).
    n_jobs : int
        Worker processes; every frequency is solved single-threaded, in a fixed order, by a
        fresh solver in a freshly spawned process, so the result does not depend on ``n_jobs``
        nor on what the calling process did before
        (Capytaine's own ``n_jobs`` splits a frequency's problems into groups, which changed
        the results by up to 2e-4 relative between 2 and 3 jobs). Capytaine is not
        bit-reproducible from run to run even so (up to 5e-6 of an array's peak, measured
        with one thread and a fixed hash seed); that is far below the discretisation error, and the
        hydro rule runs once: every later stage is bit-identical given ``platform.nc``.

    Returns
    -------
    xarray.Dataset
        See :func:`moorlife.io.platform.write_platform_nc` for the layout.
    """
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    import capytaine as cpt

    omega = np.asarray(omega, dtype=float)
    headings = np.asarray(headings, dtype=float)
    dofs = list(body.dofs)
    kw = dict(water_depth=float(water_depth), rho=float(rho), g=float(g))
    log.info("capytaine: %d faces (+lid), %d frequencies, %d headings", body.mesh.nb_faces, omega.size, headings.size)
    theta = np.linspace(0.0, 2.0 * np.pi, int(n_kochin) + 1)
    nw, nh, nt = omega.size, headings.size, theta.size
    A = np.zeros((nw, 6, 6))
    B = np.zeros((nw, 6, 6))
    F = np.zeros((nw, nh, 6), dtype=complex)  # Capytaine convention exp(-i w t)
    H_rad = np.zeros((nw, 6, nt), dtype=complex)
    H_dif = np.zeros((nw, nh, nt), dtype=complex)

    # one frequency = one unit of work, whichever process runs it (see n_jobs above)
    # each frequency in a fresh spawned process: Capytaine keeps process-level state (Green
    # function tabulation, cached decompositions, matrix caches) that made an in-process solve
    # depend on what the process had solved before (2.5e-4 relative, seen inside pytest)
    ctx = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(max_workers=max(1, int(n_jobs)), mp_context=ctx, max_tasks_per_child=1) as pool:
        jobs = [pool.submit(_solve_frequency, body, float(w), headings, theta, kw) for w in [*omega, np.inf]]
        parts = [j.result() for j in jobs]
    for iw, (a_w, b_w, f_w, hr_w, hd_w) in enumerate(parts[:-1]):
        A[iw], B[iw], F[iw], H_rad[iw], H_dif[iw] = a_w, b_w, f_w, hr_w, hd_w
    log.info("capytaine: %d frequencies solved", nw)
    A_inf = parts[-1][0]
    hs = body.compute_hydrostatic_stiffness(rho=rho, g=g).sel(influenced_dof=dofs, radiating_dof=dofs).values
    C_hydro = np.asarray(hs, dtype=float)
    # motions (Capytaine convention) and far-field mean drift
    k = wavenumber(omega, water_depth, g)
    xi = motion_rao(omega, mass_matrix, A, B, stiffness, np.conj(F))  # our convention
    drift = far_field_drift(omega, k, headings, theta, H_dif, H_rad, np.conj(xi),
                            water_depth=water_depth, rho=rho, g=g)
    attrs = {
        "source": f"capytaine {cpt.__version__}",
        "panels": int(body.mesh.nb_faces),
        "lid_panels": int(body.lid_mesh.nb_faces) if body.lid_mesh is not None else 0,
        "displaced_volume": float(body.volume),
        "center_of_buoyancy": [float(v) for v in body.center_of_buoyancy],
        "waterplane_area": float(body.waterplane_area),
        "drift_method": "far-field (Kochin functions, Maruo/Newman), surge sway yaw; heave roll pitch 0",
    }
    return platform_dataset(
        omega, headings, A, A_inf, B, np.conj(F), C_hydro, drift,
        water_depth=water_depth, rho=rho, g=g, attrs=attrs,
    )


def _solve_frequency(body: Any, omega: float, headings: np.ndarray, theta: np.ndarray,
                     kw: Mapping[str, float]) -> tuple[np.ndarray, ...]:
    """Radiation (6 dofs) and diffraction (every heading) at one frequency, single-threaded.

    Returns ``A (6,6)``, ``B (6,6)``, ``F (nh,6)`` (Capytaine convention), and the Kochin
    functions ``H_rad (6,nt)`` and ``H_dif (nh,nt)`` (empty when ``omega`` is infinite).
    """
    import capytaine as cpt
    from capytaine.bem.airy_waves import froude_krylov_force
    from capytaine.post_pro.kochin import compute_kochin
    from threadpoolctl import threadpool_limits

    dofs = list(body.dofs)
    finite = bool(np.isfinite(omega))
    problems = [cpt.RadiationProblem(body=body, omega=omega, radiating_dof=d, **kw) for d in dofs]
    if finite:
        problems += [cpt.DiffractionProblem(body=body, omega=omega, wave_direction=b, **kw) for b in headings]
    A, B = np.zeros((6, 6)), np.zeros((6, 6))
    F = np.zeros((headings.size, 6), dtype=complex)
    H_rad = np.zeros((6, theta.size), dtype=complex)
    H_dif = np.zeros((headings.size, theta.size), dtype=complex)
    with threadpool_limits(limits=1):
        results = cpt.BEMSolver().solve_all(problems, keep_details=finite, n_jobs=1, n_threads=1,
                                            progress_bar=False)
        for r in results:
            if isinstance(r.problem, cpt.RadiationProblem):
                j = dofs.index(r.radiating_dof)
                A[:, j] = [r.added_masses[d] for d in dofs]
                B[:, j] = [r.radiation_dampings[d] for d in dofs] if finite else 0.0
                if finite:
                    H_rad[j] = compute_kochin(r, theta)
            else:
                ih = int(np.argmin(np.abs(headings - r.problem.wave_direction)))
                fk = froude_krylov_force(r.problem)
                F[ih] = [r.forces[d] + fk[d] for d in dofs]
                H_dif[ih] = compute_kochin(r, theta)
    return A, B, F, H_rad, H_dif


def far_field_drift(
    omega: np.ndarray,
    k: np.ndarray,
    headings: np.ndarray,
    theta: np.ndarray,
    H_dif: np.ndarray,
    H_rad: np.ndarray,
    rao_capytaine: np.ndarray,
    *,
    water_depth: float,
    rho: float,
    g: float,
) -> np.ndarray:
    """Mean drift force per amplitude^2 from Kochin functions (far-field, Maruo/Newman).

    Capytaine's ``far_field_mean_drift_force`` restricted to unidirectional waves and vectorised.

    Parameters
    ----------
    omega, k : numpy.ndarray
        ``(nw,)`` rad/s and rad/m.
    headings : numpy.ndarray
        ``(nh,)`` rad.
    theta : numpy.ndarray
        ``(nt,)`` Kochin directions covering ``[0, 2 pi]`` inclusive, equally spaced.
    H_dif : numpy.ndarray
        ``(nw, nh, nt)`` diffraction Kochin functions (Capytaine convention).
    H_rad : numpy.ndarray
        ``(nw, 6, nt)`` radiation Kochin functions per unit motion amplitude (Capytaine's
        radiation problems prescribe a unit displacement, velocity ``-i w``).
    rao_capytaine : numpy.ndarray
        ``(nw, nh, 6)`` motion per unit amplitude in Capytaine's convention.

    Returns
    -------
    numpy.ndarray
        ``(nw, nh, 6)``, only surge, sway and yaw non-zero.
    """
    H = 1j * (H_dif + np.einsum("whd,wdt->wht", rao_capytaine, H_rad))  # (nw, nh, nt)
    dth = theta[1] - theta[0]
    dH = np.gradient(H, dth, axis=-1, edge_order=2)
    # periodic derivative at the ends
    dH[..., 0] = dH[..., -1] = (H[..., 1] - H[..., -2]) / (2 * dth)
    Hb = np.stack([[np.interp(headings[j] % (2 * np.pi), theta, H[i, j].real) + 1j * np.interp(
        headings[j] % (2 * np.pi), theta, H[i, j].imag) for j in range(H.shape[1])] for i in range(H.shape[0])])
    dHb = np.stack([[np.interp(headings[j] % (2 * np.pi), theta, dH[i, j].real) + 1j * np.interp(
        headings[j] % (2 * np.pi), theta, dH[i, j].imag) for j in range(H.shape[1])] for i in range(H.shape[0])])
    h = float(water_depth)
    coef1 = 2 * np.pi * rho * omega
    if np.isinf(h):
        coef2 = 2 * np.pi * rho * k**2
    else:
        k0 = omega**2 / g
        coef2 = 2 * np.pi * rho * k * (k0 * h) ** 2 / (h * ((k * h) ** 2 - (k0 * h) ** 2 + k0 * h))
    c1, c2 = coef1[:, None], coef2[:, None]
    absH2 = np.abs(H) ** 2
    integ = lambda f: np.trapezoid(f, theta, axis=-1)  # noqa: E731
    fx = -c1 * np.cos(headings) * Hb.imag - c2 * integ(absH2 * np.cos(theta))
    fy = -c1 * np.sin(headings) * Hb.imag - c2 * integ(absH2 * np.sin(theta))
    mz = c1 / k[:, None] * dHb.real - c2 / k[:, None] * integ(np.imag(np.conj(H) * dH))
    out = np.zeros(H.shape[:2] + (6,))
    out[..., 0], out[..., 1], out[..., 5] = fx, fy, mz
    return out


def platform_dataset(
    omega, headings, added_mass, added_mass_inf, damping, excitation, hydrostatic_stiffness, drift,
    *, water_depth: float, rho: float, g: float, attrs: Mapping | None = None,
) -> xr.Dataset:
    """Assemble the ``platform.nc`` dataset from arrays (package conventions, SI units).

    Parameters
    ----------
    omega : ``(nw,)`` rad/s; headings : ``(nh,)`` rad (propagation angle);
    added_mass, damping : ``(nw, 6, 6)``; added_mass_inf : ``(6, 6)``;
    excitation : ``(nw, nh, 6)`` complex, per unit amplitude, exp(+i w t);
    hydrostatic_stiffness : ``(6, 6)`` buoyancy + waterplane; drift : ``(nw, nh, 6)`` or None.
    """
    dof = list(DOF_NAMES)
    coords = {"omega": ("omega", np.asarray(omega, float), {"units": "rad s-1", "long_name": "wave angular frequency"}),
              "heading": ("heading", np.asarray(headings, float),
                          {"units": "rad", "long_name": "wave propagation angle, counter-clockwise from +x (east), direction of travel"}),
              "dof": ("dof", dof), RADIATING_DOF: (RADIATING_DOF, dof)}
    mat = ("omega", "dof", RADIATING_DOF)
    units_m = "kg, kg m, kg m2 (by dof pair)"
    data = {
        "added_mass": (mat, np.asarray(added_mass, float), {"units": units_m, "long_name": "radiation added mass A(omega) about the origin"}),
        "added_mass_inf": (("dof", RADIATING_DOF), np.asarray(added_mass_inf, float), {"units": units_m, "long_name": "infinite-frequency added mass"}),
        "damping": (mat, np.asarray(damping, float), {"units": "N s m-1, N s, N m s (by dof pair)", "long_name": "radiation damping B(omega)"}),
        "excitation": (("omega", "heading", "dof"), np.asarray(excitation, complex),
                       {"units": "N m-1, N (moments: N m m-1)", "long_name": "first-order wave excitation per unit amplitude",
                        "phase_convention": "exp(+i omega t) (WAMIT); eta = Re[a exp(i omega t)] at the origin"}),
        "hydrostatic_stiffness": (("dof", RADIATING_DOF), np.asarray(hydrostatic_stiffness, float),
                                  {"units": "N m-1, N, N m (by dof pair)", "long_name": "hydrostatic restoring, buoyancy and waterplane only (no -m g zG)"}),
    }
    if drift is not None:
        data["drift"] = (("omega", "heading", "dof"), np.asarray(drift, float),
                         {"units": "N m-2, N m m-2 (moments)", "long_name": "mean drift force per wave amplitude squared"})
    ds = xr.Dataset({k: xr.Variable(*v) for k, v in data.items()},
                    coords={k: xr.Variable(*v) if len(v) == 3 else xr.Variable(*v) for k, v in coords.items()})
    ds.attrs.update({"rho": float(rho), "g": float(g), "water_depth": float(water_depth),
                     "reference_point": [0.0, 0.0, 0.0],
                     "phase_convention": "exp(+i omega t) (WAMIT); Capytaine output conjugated"})
    if attrs:
        ds.attrs.update(dict(attrs))
    return ds


# ------------------------------------------------------------ rigid body, hydrostatics

def rigid_body_mass_matrix(mass: float, cm: npt.ArrayLike, inertia_cm: npt.ArrayLike) -> np.ndarray:
    """6x6 rigid-body mass matrix about the origin.

    Parameters
    ----------
    mass : float
        kg.
    cm : array_like
        ``(3,)`` centre of mass, m.
    inertia_cm : array_like
        ``(3,)`` principal moments about the CM (axes parallel to x, y, z) or ``(3, 3)``, kg m^2.

    Returns
    -------
    numpy.ndarray
        ``(6, 6)``: ``[[m I, -m S(r)], [m S(r), I_cm - m S(r) S(r)]]`` with ``S(r)`` the
        cross-product matrix of the CM position.
    """
    r = np.asarray(cm, dtype=float)
    Ic = np.asarray(inertia_cm, dtype=float)
    Ic = np.diag(Ic) if Ic.ndim == 1 else Ic
    S = np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])
    M = np.zeros((6, 6))
    M[:3, :3] = mass * np.eye(3)
    M[:3, 3:] = -mass * S
    M[3:, :3] = mass * S
    M[3:, 3:] = Ic - mass * S @ S
    return M


def system_mass_properties(platform_cfg: Mapping, source: str = "platform.yaml") -> tuple[np.ndarray, float, np.ndarray]:
    """Mass matrix of platform + ballast + tower + RNA about the origin.

    Returns
    -------
    mass_matrix : numpy.ndarray ``(6, 6)``
    total_mass : float, kg
    cg : numpy.ndarray ``(3,)``, m
    """
    M = np.zeros((6, 6))
    tot, mom = 0.0, np.zeros(3)
    for key in ("platform", "tower", "rna"):
        if key not in platform_cfg:
            raise ValueError(f"{source}: block '{key}' (mass, cm, inertia_cm) is missing")
        b = platform_cfg[key]
        for f in ("mass", "cm", "inertia_cm"):
            if f not in b:
                raise ValueError(f"{source}: {key}.{f} is missing")
        m = float(b["mass"])
        if not m > 0:
            raise ValueError(f"{source}: {key}.mass = {b['mass']!r} must be > 0")
        M += rigid_body_mass_matrix(m, b["cm"], b["inertia_cm"])
        tot += m
        mom += m * np.asarray(b["cm"], dtype=float)
    return M, tot, mom / tot


def gravity_stiffness(mass: float, cg: npt.ArrayLike, g: float) -> np.ndarray:
    """Restoring of the weight about the origin: ``-m g z_G`` in roll and pitch, and the
    roll/pitch-yaw coupling ``m g x_G``, ``m g y_G`` (WAMIT manual eq. 3.3 gravity terms).

    Returns
    -------
    numpy.ndarray ``(6, 6)``
    """
    x, y, z = np.asarray(cg, dtype=float)
    C = np.zeros((6, 6))
    C[3, 3] = C[4, 4] = -mass * g * z
    C[3, 5] = mass * g * x
    C[4, 5] = mass * g * y
    return C


def motion_rao(
    omega: np.ndarray, mass: np.ndarray, added_mass: np.ndarray, damping: np.ndarray,
    stiffness: np.ndarray, excitation: np.ndarray,
) -> np.ndarray:
    """Linear motion per unit wave amplitude, exp(+i w t) convention.

    Solves ``(-w^2 (M + A(w)) + i w B(w) + C) xi = X`` for every frequency and heading.

    Parameters
    ----------
    omega : ``(nw,)``; mass, stiffness : ``(6, 6)``; added_mass, damping : ``(nw, 6, 6)``;
    excitation : ``(nw, nh, 6)`` complex.

    Returns
    -------
    numpy.ndarray ``(nw, nh, 6)`` complex (m/m, rad/m).
    """
    w = np.asarray(omega, dtype=float)[:, None, None]
    Z = -(w**2) * (mass[None] + added_mass) + 1j * w * damping + stiffness[None]
    return np.linalg.solve(Z[:, None], excitation[..., None])[..., 0]


def natural_periods(
    mass: np.ndarray, omega: np.ndarray, added_mass: np.ndarray, stiffness: np.ndarray,
    dofs: Sequence[int] = (0, 2, 4), tol: float = 1e-8,
) -> np.ndarray:
    """Uncoupled natural periods with frequency-dependent added mass (fixed point).

    ``T_i = 2 pi sqrt((M_ii + A_ii(w_i)) / C_ii)``, iterated on ``w_i = 2 pi / T_i`` with
    ``A_ii`` interpolated in omega (held constant outside the grid).

    Returns
    -------
    numpy.ndarray ``(len(dofs),)`` periods in s.
    """
    out = []
    for i in dofs:
        if not stiffness[i, i] > 0:
            raise ValueError(f"natural_periods: stiffness[{i},{i}] = {stiffness[i, i]} is not positive")
        wn = np.sqrt(stiffness[i, i] / (mass[i, i] + added_mass[0, i, i]))
        for _ in range(200):
            a = np.interp(wn, omega, added_mass[:, i, i])
            new = np.sqrt(stiffness[i, i] / (mass[i, i] + a))
            if abs(new - wn) < tol * wn:
                break
            wn = new
        out.append(2.0 * np.pi / wn)
    return np.array(out)


# -------------------------------------------------------------------- radiation

def _extended_damping(omega: np.ndarray, damping: np.ndarray, n_fine: int) -> tuple[np.ndarray, np.ndarray]:
    # B(0) = 0 and a cosine taper over the last 10 % of the grid to 0 at omega_max: limits the
    # Gibbs ringing of the truncated transform (B(omega_max) of a semi is small but non-zero)
    w = np.concatenate([[0.0], omega])
    b = np.concatenate([np.zeros((1,) + damping.shape[1:]), damping], axis=0)
    wf = np.linspace(0.0, w[-1], n_fine)
    bf = np.empty((n_fine,) + damping.shape[1:])
    flat = b.reshape(len(w), -1)
    from scipy.interpolate import PchipInterpolator

    bf.reshape(n_fine, -1)[:] = PchipInterpolator(w, flat, axis=0)(wf)
    w_taper = 0.9 * w[-1]
    taper = np.where(wf > w_taper, 0.5 * (1 + np.cos(np.pi * (wf - w_taper) / (w[-1] - w_taper))), 1.0)
    return wf, bf * taper.reshape((-1,) + (1,) * (damping.ndim - 1))


def retardation_kernel(omega: npt.ArrayLike, damping: npt.ArrayLike, t: npt.ArrayLike, n_fine: int = 4000) -> np.ndarray:
    """Radiation impulse response ``K(t) = (2/pi) int_0^inf B(w) cos(w t) dw``.

    ``B`` is interpolated (monotone cubic) on a fine grid with ``B(0) = 0`` and tapered to
    zero over the last 10 % of the frequency range; the radiation force of the Cummins
    equation is ``-int_0^t K(t - s) xdot(s) ds``.

    Parameters
    ----------
    omega : array_like ``(nw,)`` rad/s, increasing.
    damping : array_like ``(nw, ...)``, e.g. ``(nw, 6, 6)``.
    t : array_like ``(nt,)`` s.

    Returns
    -------
    numpy.ndarray ``(nt, ...)``
    """
    omega = np.asarray(omega, dtype=float)
    damping = np.asarray(damping, dtype=float)
    t = np.asarray(t, dtype=float)
    wf, bf = _extended_damping(omega, damping, n_fine)
    c = np.cos(np.outer(t, wf))  # (nt, nf)
    wts = np.full(wf.size, wf[1] - wf[0])
    wts[[0, -1]] *= 0.5
    K = (2.0 / np.pi) * np.tensordot(c * wts, bf, axes=(1, 0))
    return K


def added_mass_infinite_ogilvie(omega: np.ndarray, added_mass: np.ndarray, t: np.ndarray, K: np.ndarray) -> np.ndarray:
    """Ogilvie's relation ``A_inf = A(w) + (1/w) int_0^inf K(t) sin(w t) dt``, averaged over w.

    Returns ``(6, 6)``; a cross-check of the BEM's infinite-frequency solve.
    """
    s = np.sin(np.outer(omega, t))  # (nw, nt)
    integ = np.trapezoid(s[:, :, None, None] * K[None], t, axis=1)
    est = added_mass + integ / omega[:, None, None]
    return est.mean(axis=0)


@dataclass(frozen=True)
class StateSpace:
    """Continuous-time radiation state space: ``dx/dt = A x + B xdot``, ``F_rad = -C x``.

    Attributes
    ----------
    A : ``(n, n)``; B : ``(n, 6)``; C : ``(6, n)``.
    kernel_error : float
        ``max |K_fit - K| / max |K|`` over the fitted kernel (all 36 terms).
    damping_error : float
        ``max_w |B_fit - B| / max |B|`` over the BEM grid below 90 % of its top frequency
        (all 36 terms; above that the kernel's damping is tapered to 0).
    """

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    kernel_error: float = float("nan")
    damping_error: float = float("nan")


def state_space_kernel(ss: StateSpace, t: npt.ArrayLike) -> np.ndarray:
    """Impulse response ``C exp(A t) B``, ``(nt, 6, 6)`` (by eigen-decomposition of ``A``)."""
    t = np.asarray(t, dtype=float)
    lam, V = np.linalg.eig(ss.A)
    CV = ss.C @ V
    VB = np.linalg.solve(V, ss.B)
    return np.einsum("in,tn,nj->tij", CV, np.exp(np.outer(t, lam)), VB).real


def state_space_response(ss: StateSpace, omega: npt.ArrayLike) -> np.ndarray:
    """Frequency response ``K(iw) = C (iw - A)^-1 B = B(w) + i w (A(w) - A_inf)``, ``(nw, 6, 6)``."""
    omega = np.asarray(omega, dtype=float)
    n = ss.A.shape[0]
    return np.stack([ss.C @ np.linalg.solve(1j * w * np.eye(n) - ss.A, ss.B) for w in omega])


def fit_state_space(
    t: np.ndarray, K: np.ndarray, order: int = 24, *, omega: np.ndarray | None = None,
    damping: np.ndarray | None = None, hankel_rows: int | None = None,
) -> StateSpace:
    """Fit a stable MIMO state space to the retardation kernel (ERA / Kung realisation).

    The kernel sampled at ``t_k = k dt`` is ``K(t_k) = C Ad^k B`` with ``Ad = exp(A dt)``; the
    block Hankel matrix of the samples is factored by SVD and truncated to ``order`` states
    (Kung 1978; Kristiansen et al. 2005 for radiation). Unstable discrete poles are reflected
    inside the unit circle. The continuous ``A = log(Ad) / dt``.

    Parameters
    ----------
    t : numpy.ndarray ``(nt,)``, equally spaced from 0.
    K : numpy.ndarray ``(nt, 6, 6)``.
    order : int
        Number of states.
    omega, damping : optional ``(nw,)``, ``(nw, 6, 6)``
        The BEM damping, to report the frequency-domain fit error.

    Returns
    -------
    StateSpace
    """
    t = np.asarray(t, dtype=float)
    dt = t[1] - t[0]
    if not np.allclose(np.diff(t), dt) or abs(t[0]) > 1e-12:
        raise ValueError("fit_state_space: t must be equally spaced and start at 0")
    nt, p, q = K.shape
    r = hankel_rows or min((nt - 1) // 2, max(order // p + 10, 30))
    c = nt - 1 - r
    H0 = np.empty((r * p, c * q))
    H1 = np.empty((r * p, c * q))
    for i in range(r):
        for j in range(c):
            H0[i * p:(i + 1) * p, j * q:(j + 1) * q] = K[i + j]
            H1[i * p:(i + 1) * p, j * q:(j + 1) * q] = K[i + j + 1]
    U, s, Vt = np.linalg.svd(H0, full_matrices=False)
    n = int(min(order, np.sum(s > s[0] * 1e-12)))
    U, s, Vt = U[:, :n], s[:n], Vt[:n]
    sq = np.sqrt(s)
    Ad = (U / sq).T @ H1 @ (Vt.T / sq)
    Bd = (sq[:, None] * Vt)[:, :q]
    Cd = (U * sq)[:p, :]
    lam, V = np.linalg.eig(Ad)
    lam = np.where(np.abs(lam) >= 1.0, 1.0 / np.conj(lam) * 0.999, lam)  # reflect unstable poles
    lam = np.where(np.abs(lam) < 1e-12, 1e-12, lam)
    Ac = (V @ np.diag(np.log(lam) / dt) @ np.linalg.inv(V))
    if np.max(np.abs(Ac.imag)) > 1e-6 * max(1.0, np.max(np.abs(Ac.real))):
        log.warning("fit_state_space: complex residue in log(Ad) (%.2e), real part kept", np.max(np.abs(Ac.imag)))
    ss = StateSpace(Ac.real, Bd, Cd)
    Kf = state_space_kernel(ss, t)
    kerr = float(np.max(np.abs(Kf - K)) / np.max(np.abs(K)))
    derr = float("nan")
    if omega is not None and damping is not None:
        # compared below 90 % of the top frequency: above it the kernel's B is tapered to 0
        band = omega <= 0.9 * omega[-1]
        Bf = state_space_response(ss, omega[band]).real
        derr = float(np.max(np.abs(Bf - damping[band])) / np.max(np.abs(damping[band])))
    return StateSpace(ss.A, ss.B, ss.C, kerr, derr)


# ----------------------------------------------------------- excitation and drift

def interp_heading(headings: np.ndarray, values: np.ndarray, heading: float) -> np.ndarray:
    """Linear interpolation in heading on the circle.

    Parameters
    ----------
    headings : ``(nh,)`` rad, increasing, any covering of the circle (wraps around).
    values : ``(nw, nh, ...)``.
    heading : float, rad (propagation angle).

    Returns
    -------
    numpy.ndarray ``(nw, ...)``
    """
    h = np.mod(np.asarray(headings, dtype=float), 2 * np.pi)
    order = np.argsort(h)
    h = h[order]
    v = np.take(values, order, axis=1)
    x = float(np.mod(heading, 2 * np.pi))
    hh = np.concatenate([h[-1:] - 2 * np.pi, h, h[:1] + 2 * np.pi])
    vv = np.concatenate([v[:, -1:], v, v[:, :1]], axis=1)
    j = int(np.searchsorted(hh, x, side="right")) - 1
    j = min(max(j, 0), hh.size - 2)
    f = (x - hh[j]) / (hh[j + 1] - hh[j])
    return (1 - f) * vv[:, j] + f * vv[:, j + 1]


def excitation_at(model: "PlatformModel", heading_rad: float) -> np.ndarray:
    """First-order excitation per unit amplitude ``(nw, 6)`` (complex, exp(+i w t)) at a heading.

    Real and imaginary parts are interpolated linearly in heading (the OC4 grid is 15 deg).
    """
    return interp_heading(model.headings, model.excitation, heading_rad)


def drift_at(model: "PlatformModel", heading_rad: float) -> np.ndarray:
    """Mean drift coefficients ``(nw, 6)`` (N/m^2) at a heading."""
    return interp_heading(model.headings, model.drift, heading_rad)


def newman_drift_force(
    t: npt.ArrayLike, amplitudes: npt.ArrayLike, omegas: npt.ArrayLike, phases: npt.ArrayLike,
    drift_coefficients: npt.ArrayLike, chunk: int = 4096,
) -> np.ndarray:
    """Slow-drift force by Newman's approximation.

    ``F(t) = sum_i sum_j a_i a_j T_ij cos((w_i - w_j) t + phi_i - phi_j)`` with
    ``T_ij = (T_ii + T_jj) / 2``, which is exactly ``Re[P(t) conj(Q(t))]`` with
    ``P = sum_i T_ii a_i exp(i(w_i t + phi_i))`` and ``Q = sum_j a_j exp(i(w_j t + phi_j))``:
    O(N) per time step, no sum-frequency content, sign changes of ``T_ii`` handled.

    Parameters
    ----------
    t : ``(nt,)`` s.
    amplitudes, omegas, phases : ``(nc,)`` wave components (m, rad/s, rad), elevation
        ``sum a cos(w t + phi)`` at the origin.
    drift_coefficients : ``(nc, ndof)`` mean drift per amplitude^2 at each component.

    Returns
    -------
    numpy.ndarray ``(nt, ndof)`` N (N m). Its time mean is ``sum a_i^2 T_ii``.
    """
    t = np.asarray(t, dtype=float)
    a = np.asarray(amplitudes, dtype=float)
    w = np.asarray(omegas, dtype=float)
    ph = np.asarray(phases, dtype=float)
    T = np.asarray(drift_coefficients, dtype=float)
    if T.ndim == 1:
        T = T[:, None]
    if not (a.shape == w.shape == ph.shape == T.shape[:1]):
        raise ValueError(f"newman_drift_force: shapes differ: a {a.shape}, omega {w.shape}, phase {ph.shape}, drift {T.shape}")
    out = np.empty((t.size, T.shape[1]))
    for s in range(0, t.size, chunk):
        e = np.exp(1j * (np.outer(t[s:s + chunk], w) + ph)) * a  # (nt, nc)
        Q = e.sum(axis=1)
        P = e @ T
        out[s:s + chunk] = (P * np.conj(Q)[:, None]).real
    return out


# ------------------------------------------------------------------------ Morison drag

def morison_elements(members: Sequence[Member], strip_length: float = 1.0) -> dict[str, np.ndarray]:
    """Split the submerged part (z < 0) of every member into drag strips.

    Returns
    -------
    dict with ``points (ne, 3)`` strip centres (m), ``axis (ne, 3)`` unit vectors,
    ``length (ne,)`` m, ``diameter (ne,)`` m, ``cd (ne,)``, and the axial (heave-plate) drag
    ``axial_points (np, 3)``, ``axial_axis (np, 3)``, ``axial_area (np,)`` m^2, ``axial_cd (np,)``.
    """
    pts, axs, lens, dias, cds = [], [], [], [], []
    ap, aa, aar, acd = [], [], [], []
    for m in members:
        a, b = m.a, m.b
        za, zb = a[2], b[2]
        if min(za, zb) >= 0.0:
            continue
        # clip to z <= 0
        s0, s1 = 0.0, 1.0
        if za > 0.0:
            s0 = za / (za - zb)
        if zb > 0.0:
            s1 = za / (za - zb)
        p0, p1 = a + s0 * (b - a), a + s1 * (b - a)
        L = float(np.linalg.norm(p1 - p0))
        n = max(1, int(np.ceil(L / strip_length)))
        f = (np.arange(n) + 0.5) / n
        pts.append(p0 + f[:, None] * (p1 - p0))
        axs.append(np.repeat(m.axis[None], n, 0))
        lens.append(np.full(n, L / n))
        dias.append(np.full(n, m.diameter))
        cds.append(np.full(n, m.cd))
        if m.axial_cd > 0 and a[2] < 0.0:
            ap.append(a)
            aa.append(m.axis)
            aar.append(0.25 * np.pi * m.diameter**2)
            acd.append(m.axial_cd)
    return {
        "points": np.concatenate(pts), "axis": np.concatenate(axs), "length": np.concatenate(lens),
        "diameter": np.concatenate(dias), "cd": np.concatenate(cds),
        "axial_points": np.asarray(ap, dtype=float).reshape(-1, 3),
        "axial_axis": np.asarray(aa, dtype=float).reshape(-1, 3),
        "axial_area": np.asarray(aar, dtype=float), "axial_cd": np.asarray(acd, dtype=float),
    }


def point_velocity(points: np.ndarray, xdot: np.ndarray) -> np.ndarray:
    """Rigid-body velocity at points, small rotations: ``v = v0 + Omega x r``.

    Parameters
    ----------
    points : ``(ne, 3)`` m; xdot : ``(..., 6)`` (m/s, rad/s).

    Returns
    -------
    numpy.ndarray ``(..., ne, 3)``
    """
    xdot = np.asarray(xdot, dtype=float)
    return xdot[..., None, :3] + np.cross(xdot[..., None, 3:], points)


def morison_drag_force(
    u_rel: np.ndarray, axis: np.ndarray, length: np.ndarray, diameter: np.ndarray, cd: np.ndarray,
    rho: float, *, axial_area: np.ndarray | None = None, axial_cd: np.ndarray | None = None,
) -> np.ndarray:
    """Quadratic drag on members (transverse) or on heave plates (axial).

    Transverse: ``f = 0.5 rho Cd D L |u_n| u_n`` with ``u_n = u - (u.e) e``.
    Axial (if ``axial_area`` is given): ``f = 0.5 rho Cd_ax A |u_a| u_a e`` with ``u_a = u.e``.

    Parameters
    ----------
    u_rel : ``(..., ne, 3)`` fluid minus structure velocity at the elements, m/s.
    axis : ``(ne, 3)`` unit vectors; length, diameter, cd : ``(ne,)`` (ignored when axial).
    rho : float, kg/m^3.

    Returns
    -------
    numpy.ndarray ``(..., ne, 3)`` N.
    """
    u = np.asarray(u_rel, dtype=float)
    e = np.asarray(axis, dtype=float)
    ua = np.einsum("...k,...k->...", u, e)
    if axial_area is not None:
        coef = 0.5 * rho * np.asarray(axial_cd) * np.asarray(axial_area)
        return (coef * np.abs(ua) * ua)[..., None] * e
    un = u - ua[..., None] * e
    speed = np.linalg.norm(un, axis=-1)
    coef = 0.5 * rho * np.asarray(cd) * np.asarray(diameter) * np.asarray(length)
    return (coef * speed)[..., None] * un


def generalised_force(points: np.ndarray, forces: np.ndarray) -> np.ndarray:
    """Sum of point forces as a 6-dof load about the origin, ``(..., 6)`` (N, N m)."""
    f = np.asarray(forces, dtype=float)
    return np.concatenate([f.sum(axis=-2), np.cross(points, f).sum(axis=-2)], axis=-1)


# ------------------------------------------------------------- the simulator's model

@dataclass(frozen=True)
class PlatformModel:
    """Everything the time-domain integrator needs, as arrays (SI units, origin at SWL).

    Equation of motion (Cummins), ``x`` the 6 dofs about the origin::

        (mass + added_mass_inf) xddot + C_ss x_r + stiffness x
            = F_exc(t) + F_drift(t) + F_morison + F_mooring + F_thrust
        dx_r/dt = ss_A x_r + ss_B xdot          (radiation force = -ss_C @ x_r)

    or, with the kernel, radiation force ``= -sum K(t_k) xdot(t - t_k) kernel_dt``.

    Attributes
    ----------
    mass : ``(6, 6)`` platform + ballast + tower + RNA about the origin, kg / kg m / kg m^2.
    total_mass : float, kg; cg : ``(3,)`` m.
    added_mass_inf : ``(6, 6)``.
    hydrostatic_stiffness : ``(6, 6)`` buoyancy + waterplane (as WAMIT .hst).
    stiffness : ``(6, 6)`` hydrostatic + gravity (``-m g z_G``); no mooring.
    ss_A ``(n, n)``, ss_B ``(n, 6)``, ss_C ``(6, n)``: radiation state space;
    ss_kernel_error, ss_damping_error : float, relative fit errors (see :class:`StateSpace`).
    kernel_t ``(nt,)`` s, kernel ``(nt, 6, 6)``, kernel_dt : float: the retardation kernel.
    omega ``(nw,)`` rad/s, headings ``(nh,)`` rad (propagation angle),
    excitation ``(nw, nh, 6)`` complex per unit amplitude, exp(+i w t),
    drift ``(nw, nh, 6)`` N/m^2, added_mass / damping ``(nw, 6, 6)``.
    morison_points ``(ne, 3)``, morison_axis ``(ne, 3)``, morison_length, morison_diameter,
    morison_cd ``(ne,)``; axial_points ``(np, 3)``, axial_axis ``(np, 3)``, axial_area,
    axial_cd ``(np,)`` (heave plates).
    rho, g, water_depth : environment; rho_air : kg/m^3.
    hub_point ``(3,)`` m, hub_height m, rotor_radius m, rotor_area m^2,
    ct_wind_speed, ct ``(nct,)``, cut_in, cut_out, shutdown_ramp, startup_ramp m/s,
    pitch_natural_frequency rad/s (with the linear OC4 mooring), pitch_filter_centre rad/s,
    pitch_filter_quality.
    """

    mass: np.ndarray
    total_mass: float
    cg: np.ndarray
    added_mass_inf: np.ndarray
    hydrostatic_stiffness: np.ndarray
    stiffness: np.ndarray
    ss_A: np.ndarray
    ss_B: np.ndarray
    ss_C: np.ndarray
    ss_kernel_error: float
    ss_damping_error: float
    kernel_t: np.ndarray
    kernel: np.ndarray
    kernel_dt: float
    omega: np.ndarray
    headings: np.ndarray
    excitation: np.ndarray
    drift: np.ndarray
    added_mass: np.ndarray
    damping: np.ndarray
    morison_points: np.ndarray
    morison_axis: np.ndarray
    morison_length: np.ndarray
    morison_diameter: np.ndarray
    morison_cd: np.ndarray
    axial_points: np.ndarray
    axial_axis: np.ndarray
    axial_area: np.ndarray
    axial_cd: np.ndarray
    rho: float
    g: float
    water_depth: float
    rho_air: float
    hub_point: np.ndarray
    hub_height: float
    rotor_radius: float
    rotor_area: float
    ct_wind_speed: np.ndarray
    ct: np.ndarray
    cut_in: float
    cut_out: float
    shutdown_ramp: float
    startup_ramp: float
    pitch_natural_frequency: float
    pitch_filter_centre: float
    pitch_filter_quality: float
    mooring_stiffness: np.ndarray = field(default_factory=lambda: np.zeros((6, 6)))


def load_platform_model(
    platform: xr.Dataset,
    platform_cfg: Mapping,
    *,
    kernel_duration: float = 80.0,
    kernel_dt: float = 0.2,
    ss_order: int | None = 30,
    source: str = "platform.yaml",
) -> PlatformModel:
    """Build the simulator's :class:`PlatformModel` from ``platform.nc`` and ``platform.yaml``.

    Parameters
    ----------
    platform : xarray.Dataset
        As read by :func:`moorlife.io.platform.open_platform_nc` (complex ``excitation``).
    platform_cfg : mapping
        ``platform.yaml`` content.
    kernel_duration, kernel_dt : float
        Length and step of the retardation kernel, s.
    ss_order : int or None
        Order of the radiation state space; None skips the fit (5-16 s) when the simulator
        uses the convolution, and leaves empty ``ss_*`` arrays with NaN fit errors.
    """
    from moorlife.turbine import ct_table

    for v in ("added_mass", "added_mass_inf", "damping", "excitation", "hydrostatic_stiffness"):
        if v not in platform:
            raise ValueError(f"platform dataset: variable '{v}' is missing")
    env = platform_cfg["environment"]
    rho, g = float(platform.attrs.get("rho", env["rho_water"])), float(platform.attrs.get("g", env["gravity"]))
    M, mtot, cg = system_mass_properties(platform_cfg, source)
    omega = platform["omega"].values
    A = platform["added_mass"].transpose("omega", "dof", RADIATING_DOF).values
    B = platform["damping"].transpose("omega", "dof", RADIATING_DOF).values
    Ainf = platform["added_mass_inf"].transpose("dof", RADIATING_DOF).values
    Ch = platform["hydrostatic_stiffness"].transpose("dof", RADIATING_DOF).values
    X = platform["excitation"].transpose("omega", "heading", "dof").values
    D = (platform["drift"].transpose("omega", "heading", "dof").values if "drift" in platform
         else np.zeros(X.shape))
    C = Ch + gravity_stiffness(mtot, cg, g)
    t = np.arange(0.0, kernel_duration + 0.5 * kernel_dt, kernel_dt)
    K = retardation_kernel(omega, B, t)
    if ss_order is None:
        ss_a, ss_b, ss_c, ss_errs = np.zeros((0, 0)), np.zeros((0, 6)), np.zeros((6, 0)), (np.nan, np.nan)
    else:
        step = max(1, int(round(0.5 / kernel_dt)))  # fit on a 0.5 s sampling: small Hankel matrix
        ss = fit_state_space(t[::step], K[::step], ss_order, omega=omega, damping=B)
        ss_a, ss_b, ss_c, ss_errs = ss.A, ss.B, ss.C, (ss.kernel_error, ss.damping_error)
    mem = members_from_config(platform_cfg, source)
    el = morison_elements(mem, float(platform_cfg.get("morison_strip_length", 1.0)))
    tcfg = platform_cfg["turbine"]
    ws, ct = ct_table(tcfg, source)
    Km = np.diag(np.asarray(platform_cfg.get("mooring_stiffness_diag", [0.0] * 6), dtype=float))
    (Tp,) = natural_periods(M, omega, A, C + Km, dofs=(4,))
    wp = 2.0 * np.pi / Tp
    fc = tcfg.get("pitch_filter", {}) or {}
    centre = float(fc["centre"]) if fc.get("centre") is not None else wp
    R = float(tcfg["rotor_radius"])
    return PlatformModel(
        mass=M, total_mass=mtot, cg=cg, added_mass_inf=Ainf, hydrostatic_stiffness=Ch, stiffness=C,
        ss_A=ss_a, ss_B=ss_b, ss_C=ss_c, ss_kernel_error=ss_errs[0], ss_damping_error=ss_errs[1],
        kernel_t=t, kernel=K, kernel_dt=float(kernel_dt),
        omega=omega, headings=platform["heading"].values, excitation=X, drift=D, added_mass=A, damping=B,
        morison_points=el["points"], morison_axis=el["axis"], morison_length=el["length"],
        morison_diameter=el["diameter"], morison_cd=el["cd"], axial_points=el["axial_points"],
        axial_axis=el["axial_axis"], axial_area=el["axial_area"], axial_cd=el["axial_cd"],
        rho=rho, g=g, water_depth=float(platform.attrs.get("water_depth", env["water_depth"])),
        rho_air=float(env.get("rho_air", 1.225)),
        hub_point=np.array([0.0, 0.0, float(tcfg["hub_height"])]), hub_height=float(tcfg["hub_height"]),
        rotor_radius=R, rotor_area=np.pi * R**2, ct_wind_speed=ws, ct=ct,
        cut_in=float(tcfg["cut_in"]), cut_out=float(tcfg["cut_out"]),
        shutdown_ramp=float(tcfg.get("shutdown_ramp", 1.0)), startup_ramp=float(tcfg.get("startup_ramp", 1.0)),
        pitch_natural_frequency=float(wp), pitch_filter_centre=centre,
        pitch_filter_quality=float(fc.get("quality", 1.0)), mooring_stiffness=Km,
    )


def richardson(fine: xr.Dataset, coarse: xr.Dataset, ratio: float = 2.0) -> xr.Dataset:
    """First-order Richardson extrapolation in panel size of the hydrodynamic coefficients.

    A constant-panel BEM converges linearly in the panel size ``h`` near sharp edges (the
    heave-plate rims): ``F(h) = F0 + c h``. With ``F(h)`` and ``F(ratio h)``:
    ``F0 = F(h) + (F(h) - F(ratio h)) / (ratio - 1)``. Applied to ``added_mass``,
    ``added_mass_inf``, ``damping``, ``excitation`` and ``drift``; hydrostatics are kept from
    the fine mesh (exact to its polygons).
    """
    out = fine.copy()
    f = 1.0 / (float(ratio) - 1.0)
    for v in ("added_mass", "added_mass_inf", "damping", "excitation", "drift"):
        if v in fine and v in coarse:
            out[v] = (fine[v] + f * (fine[v] - coarse[v])).assign_attrs(fine[v].attrs)
    out.attrs["richardson"] = f"F(h) + (F(h) - F({ratio:g} h)) / {ratio - 1:g}, h = {fine.attrs.get('panel_size')} m"
    return out


def bem_from_settings(settings: Mapping, n_jobs: int = 1) -> xr.Dataset:
    """Run the BEM described by :func:`bem_settings` (the ``hydro`` rule's params).

    With ``settings["richardson"]`` the BEM is also run at twice the panel size and the
    coefficients are extrapolated to zero panel size (:func:`richardson`).

    Returns
    -------
    xarray.Dataset
        The ``platform.nc`` dataset, with the settings' mesh information in its attributes.
    """
    ds = _bem_one_mesh(settings, float(settings["panel_size"]), n_jobs)
    if settings.get("richardson"):
        coarse = _bem_one_mesh(settings, 2.0 * float(settings["panel_size"]), n_jobs)
        ds = richardson(ds, coarse, 2.0)
    return ds


def _bem_one_mesh(settings: Mapping, panel_size: float, n_jobs: int) -> xr.Dataset:
    env = settings["environment"]
    members = members_from_config({"members": settings["members"]}, "hydro params")
    om = settings["omega"]
    omega = frequency_grid(om["min"], om["max"], om["n"])
    headings = heading_grid(settings["heading_step"])
    M, mtot, cg = system_mass_properties(settings["bodies"], "hydro params")
    around = float(settings.get("around_refinement", 1.0))  # omitted at its default (bem_settings)
    body = capytaine_body(members, panel_size, rotational_symmetry=settings.get("rotational_symmetry"),
                          lid=settings["irregular_frequency_removal"], around=around)
    rho, g, h = float(env["rho_water"]), float(env["gravity"]), float(env["water_depth"])
    Ch = np.asarray(body.compute_hydrostatic_stiffness(rho=rho, g=g).values, dtype=float)
    C = Ch + gravity_stiffness(mtot, cg, g) + np.diag(np.asarray(settings["mooring_stiffness_diag"], dtype=float))
    ds = run_bem(body, omega, headings, water_depth=h, rho=rho, g=g, mass_matrix=M, stiffness=C,
                 n_kochin=settings["kochin_directions"], n_jobs=n_jobs)
    ds.attrs.update({"panel_size": float(panel_size),
                     "around_refinement": around,
                     "rotational_symmetry": int(settings.get("rotational_symmetry") or 0),
                     "irregular_frequency_removal": int(bool(settings["irregular_frequency_removal"]))})
    return ds
