"""ar and gauss_markov against statsmodels on the same arrays (1e-9)."""

import numpy as np
import pytest
from statsmodels.regression.linear_model import burg, yule_walker
from statsmodels.tsa.ar_model import AutoReg

import thermonav


@pytest.fixture(scope="module")
def ma1(shared):
    """statsmodels' Burg test series: y[t] = e[t+1] + 0.5 e[t], 10 000 values."""
    return np.loadtxt(shared / "statsmodels" / "burg_ma1_series.txt")


@pytest.fixture(scope="module")
def one_second_means(adis):
    """Gyro_X of the ADIS16405 averaged over 1 s blocks (1000 values, deg/s)."""
    return adis["Gyro_X"].reshape(-1, 100).mean(axis=1)


def series(ma1, one_second_means):
    return {"ma1": ma1, "adis_1s": one_second_means}


@pytest.mark.parametrize("order", [1, 2, 3, 5])
@pytest.mark.parametrize("name", ["ma1", "adis_1s"])
def test_burg_equals_statsmodels(order, name, ma1, one_second_means):
    x = series(ma1, one_second_means)[name]
    ours = thermonav.ar(x, "burg", order)
    coefficients, sigma2 = burg(x, order, demean=True)
    np.testing.assert_allclose(ours.coefficients, coefficients, rtol=0, atol=1e-9)
    assert ours.noise_variance == pytest.approx(sigma2, rel=1e-9)
    assert ours.order == order and ours.method == "burg"


@pytest.mark.parametrize("order", [1, 2, 3, 5])
@pytest.mark.parametrize("name", ["ma1", "adis_1s"])
def test_yule_walker_equals_statsmodels_mle(order, name, ma1, one_second_means):
    x = series(ma1, one_second_means)[name]
    ours = thermonav.ar(x, "yule-walker", order)
    coefficients, sigma = yule_walker(x, order, method="mle", demean=True, result_object=False)
    np.testing.assert_allclose(ours.coefficients, coefficients, rtol=0, atol=1e-9)
    assert ours.noise_variance == pytest.approx(sigma**2, rel=1e-9)


@pytest.mark.parametrize("order", [1, 3])
def test_covariance_method_equals_statsmodels_autoreg_on_the_demeaned_series(order, ma1):
    # Forward least squares over k = p..N-1 of the demeaned series is AutoReg without trend;
    # the noise variance divides by N - p (AutoReg's sigma2 by its nobs, also N - p).
    ours = thermonav.ar(ma1, "covariance", order)
    fit = AutoReg(ma1 - ma1.mean(), order, trend="n").fit()
    np.testing.assert_allclose(ours.coefficients, fit.params, rtol=0, atol=1e-9)
    assert ours.noise_variance == pytest.approx(fit.sigma2, rel=1e-9)


def test_auto_order_and_the_ar_based_gauss_markov(one_second_means):
    ours = thermonav.ar(one_second_means, "burg", "auto", max_order=4, dt_s=1.0)
    assert 1 <= ours.order <= 4
    gm = ours.gauss_markov
    c1 = burg(one_second_means, 1, demean=True)[0][0]
    assert gm.c1 == pytest.approx(c1, abs=1e-9)
    assert gm.status == "model"
    assert gm.correlation_time_s == pytest.approx(-1.0 / np.log(c1), rel=1e-9)


def test_gauss_markov_ar_based_is_the_burg_ar1_on_the_median_interval(one_second_means):
    t = np.arange(len(one_second_means), dtype=float)
    gm = thermonav.gauss_markov(t, one_second_means, family="ar_based")
    c1 = burg(one_second_means, 1, demean=True)[0][0]
    assert gm.family == "ar_based" and gm.sample_interval_s == 1.0
    assert gm.correlation_time_s == pytest.approx(-1.0 / np.log(c1), rel=1e-9)


def simulated_gauss_markov(tc_s, dt_s, n, white_sd, seed):
    rng = np.random.default_rng(seed)
    phi = np.exp(-dt_s / tc_s)
    drive = rng.standard_normal(n) * np.sqrt(1 - phi**2)
    bias = np.zeros(n)
    for k in range(1, n):
        bias[k] = phi * bias[k - 1] + drive[k]
    return bias + white_sd * rng.standard_normal(n)


def test_the_exact_likelihood_recovers_correlation_times_inside_their_intervals():
    # A unit-sigma Gauss-Markov bias with Tc = 50 s seen through as much white noise, 2 Hz,
    # 2 h, ten seeds: a 95 % interval misses one record in twenty, so at least 8 of 10 must
    # cover (7 or fewer has a binomial probability of 0.012).
    dt_s, tc_s = 0.5, 50.0
    covered = 0
    for seed in range(10, 20):
        x = simulated_gauss_markov(tc_s, dt_s, 14_400, white_sd=1.0, seed=seed)
        gm = thermonav.gauss_markov(np.arange(len(x)) * dt_s, x)
        assert gm.family == "irregular_ml" and gm.status == "model"
        assert gm.n_samples == len(x)
        low, high = gm.ci95_correlation_time_s
        covered += low <= tc_s <= high
    assert covered >= 8


def test_acf_fit_of_a_plain_gauss_markov_series():
    x = simulated_gauss_markov(20.0, 1.0, 20_000, white_sd=0.0, seed=3)
    gm = thermonav.gauss_markov(np.arange(len(x), dtype=float), x, family="acf_fit")
    assert gm.status == "model"
    assert gm.correlation_time_s == pytest.approx(20.0, rel=0.3)
