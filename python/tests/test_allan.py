"""allan and noise_terms against allantools on the same arrays (relative 1e-9)."""

import allantools
import numpy as np
import pytest

import thermonav

PEERS = {
    "adev": allantools.oadev,
    "mdev": allantools.mdev,
    "hdev": allantools.hdev,
    "ohdev": allantools.ohdev,
    "tdev": allantools.tdev,
    "totdev": allantools.totdev,
}


def assert_same_curve(ours, kind, x, rate_hz):
    tau, dev, _, n = PEERS[kind](x, rate=rate_hz, data_type="freq", taus="octave")
    k = len(ours.tau_s)
    assert k >= 3 and len(tau) == k
    np.testing.assert_allclose(ours.tau_s, tau, rtol=1e-12)
    # Same estimator, other summation order: agreement to rounding, 1e-9 leaves margin.
    np.testing.assert_allclose(ours[kind], dev, rtol=1e-9)
    np.testing.assert_array_equal(ours.n_terms, n)


@pytest.mark.parametrize("kind", list(PEERS))
def test_every_kind_equals_allantools_on_a_generated_series(kind, generated):
    ours = thermonav.allan(generated, 50.0, kind=kind)
    assert ours.kind == kind
    assert_same_curve(ours, kind, generated, 50.0)


@pytest.mark.parametrize("kind", list(PEERS))
@pytest.mark.parametrize("column", ["Gyro_X", "Accel_Z"])
def test_every_kind_equals_allantools_on_the_static_adis16405(kind, column, adis):
    ours = thermonav.allan(adis[column], 100.0, kind=kind)
    assert_same_curve(ours, kind, adis[column], 100.0)


def test_adev_has_limits_around_the_curve_and_attribute_access(generated):
    curve = thermonav.allan(generated, 50.0)
    assert curve.adev is curve["adev"]
    assert np.all(curve.ci_low <= curve.adev) and np.all(curve.adev <= curve.ci_high)
    assert curve.confidence == pytest.approx(0.683)
    assert len(curve.noise_type_alpha) == len(curve.tau_s) == len(curve.edf)


def test_explicit_averaging_factors(generated):
    curve = thermonav.allan(generated, 50.0, taus=[1, 3, 10, 33])
    np.testing.assert_array_equal(curve.averaging_factor, [1, 3, 10, 33])
    tau, dev, _, _ = allantools.oadev(
        generated, rate=50.0, data_type="freq", taus=np.array([1, 3, 10, 33]) / 50.0
    )
    np.testing.assert_allclose(curve.adev, dev, rtol=1e-9)


def test_a_strided_array_gives_the_curve_of_its_copy(generated):
    strided = generated[::2]
    assert not strided.flags.c_contiguous
    a = thermonav.allan(strided, 25.0)
    b = thermonav.allan(np.ascontiguousarray(strided), 25.0)
    np.testing.assert_array_equal(a.adev, b.adev)


def test_white_noise_density_of_a_white_gyro():
    # Pure white noise of density N rad/sqrt(s) at 100 Hz: sd = N sqrt(100).
    density = 1e-3
    x = np.random.default_rng(7).standard_normal(200_000) * density * np.sqrt(100.0)
    terms = thermonav.noise_terms(x, 100.0, "gyro")
    n = terms.random_walk
    assert n.unit_si == "rad/sqrt(s)" and n.unit == "deg/sqrt(h)"
    assert n.value_si == pytest.approx(density, rel=0.03)
    assert n.ci_low_si <= n.value_si <= n.ci_high_si
    assert n.value == pytest.approx(np.degrees(n.value_si) * 60.0)
    assert set(terms) == {
        "quantization", "random_walk", "bias_instability", "rate_random_walk", "rate_ramp", "absent"
    }
    assert all(isinstance(reason, str) for reason in terms.absent.values())
