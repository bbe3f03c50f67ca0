"""WAMIT readers: each test writes its own small file in WAMIT layout with known
dimensional values, nondimensionalised by hand (WAMIT User Manual v7 section 4.1), so a wrong
exponent, density, gravity or period/frequency mix-up fails."""

from __future__ import annotations

import numpy as np
import pytest

from moorlife.io.wamit import read_wamit_1, read_wamit_3, read_wamit_12d, read_wamit_dataset, read_wamit_hst

RHO, G, L = 1000.0, 10.0, 2.0  # deliberately not 1025 / 9.80665 / 1 so every scale shows


def _k(i, j, base):
    return base + (i >= 4) + (j >= 4)


def _write_1(path, periods, A, B, A_inf, A_zero, pairs):
    lines = []
    for per, mat in ((0.0, A_inf), (-1.0, A_zero)):  # WAMIT: zero period = infinite frequency
        for i, j in pairs:
            lines.append(f"{per:14.6E} {i:5d} {j:5d} {mat[i - 1, j - 1] / (RHO * L ** _k(i, j, 3)):14.6E}")
    for n, per in enumerate(periods):
        w = 2 * np.pi / per
        for i, j in pairs:
            k = _k(i, j, 3)
            lines.append(
                f"{per:14.6E} {i:5d} {j:5d} {A[n, i - 1, j - 1] / (RHO * L**k):14.6E} "
                f"{B[n, i - 1, j - 1] / (RHO * L**k * w):14.6E}"
            )
    path.write_text("\n".join(lines) + "\n")


@pytest.fixture
def one_file(tmp_path):
    pairs = [(1, 1), (1, 5), (3, 3), (5, 1), (5, 5), (6, 6)]
    periods = np.array([20.0, 10.0, 5.0])  # written in decreasing period (increasing omega)
    rng = np.random.default_rng(1)
    A = np.zeros((3, 6, 6))
    B = np.zeros((3, 6, 6))
    for i, j in pairs:
        A[:, i - 1, j - 1] = rng.uniform(1e5, 1e9, 3)
        B[:, i - 1, j - 1] = rng.uniform(1e3, 1e7, 3)
    A_inf = A[-1] * 0.9
    A_zero = A[0] * 1.1
    p = tmp_path / "body.1"
    _write_1(p, periods, A, B, A_inf, A_zero, pairs)
    return p, periods, A, B, A_inf, A_zero


def test_read_1_redimensionalises(one_file):
    p, periods, A, B, A_inf, A_zero = one_file
    omega, a, b, ainf, azero = read_wamit_1(p, rho=RHO, g=G, ulen=L)
    np.testing.assert_allclose(omega, 2 * np.pi / periods, rtol=1e-12)
    np.testing.assert_allclose(a, A, rtol=1e-6)
    np.testing.assert_allclose(b, B, rtol=1e-6)
    np.testing.assert_allclose(ainf, A_inf, rtol=1e-6)
    np.testing.assert_allclose(azero, A_zero, rtol=1e-6)


def test_read_1_limits_follow_the_physics(tmp_path):
    """The row read as A_inf is the w -> inf limit of the finite-frequency data (Ogilvie), and
    the one read as A(0) their w -> 0 limit: a causal two-pole body in WAMIT's layout."""
    from moorlife.hydro import added_mass_infinite_ogilvie, retardation_kernel

    # radiation impedance of one damped mode, Z(iw) = c iw / (w0^2 - w^2 + 2 i zeta w0 w) =
    # B(w) + iw (A(w) - A_inf): causal, B(0) = 0, A(0) - A_inf = c / w0^2 = 2e6 kg
    a_inf, w0, zeta = 5e6, 0.8, 0.3
    c = 2e6 * w0**2
    periods = 2 * np.pi / np.linspace(0.05, 40.0, 800)[::-1]
    w = 2 * np.pi / periods

    def curves(om):
        z = c * 1j * om / (w0**2 - om**2 + 2j * zeta * w0 * om)
        return a_inf + (c * (w0**2 - om**2) / np.abs(w0**2 - om**2 + 2j * zeta * w0 * om) ** 2), z.real

    A, B = np.zeros((w.size, 6, 6)), np.zeros((w.size, 6, 6))
    A[:, 0, 0], B[:, 0, 0] = curves(w)
    lim = {k: np.zeros((6, 6)) for k in ("inf", "zero")}
    lim["inf"][0, 0], lim["zero"][0, 0] = a_inf, curves(np.array([0.0]))[0][0]
    p = tmp_path / "causal.1"
    _write_1(p, periods, A, B, lim["inf"], lim["zero"], [(1, 1)])
    omega, a, b, ainf, azero = read_wamit_1(p, rho=RHO, g=G, ulen=L)
    t = np.arange(0.0, 120.0, 0.05)
    K = retardation_kernel(omega, b, t)
    band = (omega > 0.3) & (omega < 3.0)
    ogilvie = added_mass_infinite_ogilvie(omega[band], a[band], t, K)
    assert ainf[0, 0] == pytest.approx(ogilvie[0, 0], rel=5e-3)
    assert azero[0, 0] == pytest.approx(a[0, 0, 0], rel=2e-3)  # 0.05 rad/s is close to the zero-frequency limit
    assert abs(azero[0, 0] / ainf[0, 0] - 1) > 0.2  # the two limits are far apart, so a swap fails


def test_read_1_sorts_by_frequency(tmp_path, one_file):
    p, periods, A, B, *_ = one_file
    lines = p.read_text().splitlines()
    head, body = lines[:12], lines[12:]
    shuffled = body[12:] + body[:12]  # 5 s and 10 s rows before the 20 s rows
    q = tmp_path / "shuffled.1"
    q.write_text("\n".join(head + shuffled) + "\n")
    omega, a, b, *_ = read_wamit_1(q, rho=RHO, g=G, ulen=L)
    assert np.all(np.diff(omega) > 0)
    np.testing.assert_allclose(a, A, rtol=1e-6)


def test_read_1_errors_name_file_and_row(tmp_path):
    p = tmp_path / "bad.1"
    p.write_text("  10.0  1  1  1.0  2.0\n  10.0  7  1  1.0  2.0\n")
    with pytest.raises(ValueError, match=r"bad\.1: data row 2: I = 7"):
        read_wamit_1(p)
    p.write_text("  10.0  1  1  1.0  2.0\n  10.0  1  x  1.0  2.0\n")
    with pytest.raises(ValueError, match=r"bad\.1: line 2: not numeric"):
        read_wamit_1(p)
    p.write_text("  10.0  1  1  1.0\n")
    with pytest.raises(ValueError, match="finite-period rows need 5 columns"):
        read_wamit_1(p)
    with pytest.raises(FileNotFoundError, match="nothere.1"):
        read_wamit_1(tmp_path / "nothere.1")


def _write_3(path, periods, betas, X):
    lines = []
    for n, per in enumerate(periods):
        for h, beta in enumerate(betas):
            for i in range(1, 7):
                m = 2 if i <= 3 else 3
                xb = X[n, h, i - 1] / (RHO * G * L**m)
                lines.append(
                    f"{per:14.6E} {beta:14.6E} {i:5d} {abs(xb):14.6E} {np.angle(xb, deg=True):14.6E} "
                    f"{xb.real:14.6E} {xb.imag:14.6E}"
                )
    path.write_text("\n".join(lines) + "\n")


def test_read_3_headings_and_complex_values(tmp_path):
    periods = np.array([12.0, 6.0])
    betas = np.array([-180.0, -90.0, 0.0, 90.0, 180.0])  # -180 and 180 are the same heading
    rng = np.random.default_rng(2)
    X = (rng.normal(size=(2, 5, 6)) + 1j * rng.normal(size=(2, 5, 6))) * 1e6
    X[:, 4] = X[:, 0]
    p = tmp_path / "body.3"
    _write_3(p, periods, betas, X)
    omega, heads, x = read_wamit_3(p, rho=RHO, g=G, ulen=L)
    np.testing.assert_allclose(omega, 2 * np.pi / periods)
    np.testing.assert_allclose(np.rad2deg(heads), [0.0, 90.0, 180.0, 270.0])
    # 0 deg is column 2 of the file, 270 deg (= -90) is column 1, 180 deg is column 0
    np.testing.assert_allclose(x[:, 0], X[:, 2], rtol=1e-5)
    np.testing.assert_allclose(x[:, 3], X[:, 1], rtol=1e-5)
    np.testing.assert_allclose(x[:, 2], X[:, 0], rtol=1e-5)
    # phases kept as written (WAMIT exp(+i w t) is the package convention): no conjugation
    assert np.sign(x[0, 0, 0].imag) == np.sign(X[0, 2, 0].imag)


def test_read_3_missing_value(tmp_path):
    X = np.ones((1, 2, 6), dtype=complex)
    p = tmp_path / "hole.3"
    _write_3(p, np.array([10.0]), np.array([0.0, 90.0]), X)
    lines = p.read_text().splitlines()
    p.write_text("\n".join(lines[:-1]) + "\n")  # drop (90 deg, dof 6)
    with pytest.raises(ValueError, match=r"hole\.3: no value for period 10 s, heading 90 deg, dof 6"):
        read_wamit_3(p)


def test_read_hst_exponents(tmp_path):
    C = np.zeros((6, 6))
    C[2, 2], C[2, 4], C[4, 2], C[3, 3], C[4, 4] = 3.8e6, -1.5e3, -1.5e3, -3.8e8, -3.7e8
    lines = []
    for i in range(1, 7):
        for j in range(1, 7):
            lines.append(f"{i:6d}{j:6d}  {C[i - 1, j - 1] / (RHO * G * L ** _k(i, j, 2)):14.6E}")
    p = tmp_path / "body.hst"
    p.write_text("\n".join(lines) + "\n")
    np.testing.assert_allclose(read_wamit_hst(p, rho=RHO, g=G, ulen=L), C, rtol=1e-6)


def _write_12d(path, periods, drift, beta=0.0, header=True):
    lines = [" WAMIT Numeric Output -- Filename  body.12d"] if header else []
    for n, per in enumerate(periods):
        for per2 in periods:  # off-diagonal rows must be ignored
            for i in (1, 2, 3, 5, 6):
                m = 1 if i <= 3 else 2
                val = drift[n, i - 1] / (RHO * G * L**m) if per2 == per else 99.0
                lines.append(
                    f"{per:14.5E} {per2:14.5E} {beta:14.5E} {beta:14.5E} {i:4d} {abs(val):12.5E} "
                    f"{0.0 if val >= 0 else 180.0:12.5E} {val:12.5E} {0.5:12.5E}"
                )
    path.write_text("\n".join(lines) + "\n")


def test_read_12d_mean_drift_diagonal(tmp_path):
    periods = np.array([20.0, 10.0, 8.0])
    drift = np.zeros((3, 6))
    drift[:, 0] = [1.0e3, 5.0e4, -2.0e3]
    drift[:, 2] = [10.0, 20.0, 30.0]
    drift[:, 4] = [1e5, 2e5, 3e5]
    p = tmp_path / "body.12d"
    _write_12d(p, periods, drift)
    omega, heads, d = read_wamit_12d(p, rho=RHO, g=G, ulen=L)
    np.testing.assert_allclose(omega, 2 * np.pi / periods, rtol=1e-5)
    np.testing.assert_allclose(heads, [0.0])
    np.testing.assert_allclose(d[:, 0], drift, rtol=1e-5, atol=1e-9)


def test_read_dataset_assembles_and_checks_grids(tmp_path, one_file):
    p1, periods, A, B, A_inf, _ = one_file
    prefix = str(p1)[:-2]
    X = np.ones((3, 2, 6), dtype=complex) * (1 + 2j) * 1e5
    _write_3(tmp_path / "body.3", periods, np.array([0.0, 180.0]), X)
    C = np.zeros((6, 6))
    C[2, 2] = 4e6
    (tmp_path / "body.hst").write_text(f"3 3 {4e6 / (RHO * G * L**2):.8E}\n")
    drift = np.zeros((3, 6))
    drift[:, 0] = [1e3, 2e3, 3e3]
    _write_12d(tmp_path / "body.12d", periods, drift)
    ds = read_wamit_dataset(prefix, rho=RHO, g=G, ulen=L)
    np.testing.assert_allclose(ds["added_mass"].values, A, rtol=1e-6)
    np.testing.assert_allclose(ds["added_mass_inf"].values, A_inf, rtol=1e-6)
    np.testing.assert_allclose(ds["hydrostatic_stiffness"].values, C, rtol=1e-6)
    np.testing.assert_allclose(ds["excitation"].values, X, rtol=1e-5)
    # one-heading .12d: the horizontal drift turns with the waves (180 deg: reversed surge)
    np.testing.assert_allclose(ds["drift"].isel(heading=0, dof=0).values, drift[:, 0], rtol=1e-5)
    np.testing.assert_allclose(ds["drift"].isel(heading=1, dof=0).values, -drift[:, 0], rtol=1e-5)
    # a .3 on another frequency grid is refused
    _write_3(tmp_path / "body.3", periods[:2], np.array([0.0]), X[:2, :1])
    with pytest.raises(ValueError, match="frequency grids differ"):
        read_wamit_dataset(prefix, rho=RHO, g=G, ulen=L)
