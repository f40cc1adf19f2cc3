"""Oracle for the power of the two-sided paired t-test and the pairs it needs: statsmodels'
TTestPower (the noncentral t distribution of scipy). Printed values are pasted into
crates/thermonav/src/evaluation/significance.rs's tests.
Run once: python3 tools/oracles/paired_t_power.py"""
import statsmodels
from statsmodels.stats.power import TTestPower

power = TTestPower()
print(f"statsmodels {statsmodels.__version__}")
print("power(effect size, pairs, alpha):")
for d, n, alpha in [(0.5, 10, 0.05), (1.0, 8, 0.01), (1.5, 5, 0.01), (0.3, 60, 0.01), (2.5, 3, 0.01)]:
    print(f"  ({d}, {n}, {alpha}, {power.power(effect_size=d, nobs=n, alpha=alpha):.10f}),")
print("pairs for 80 % power at alpha 0.01 (statsmodels' real-valued solution):")
for d in [0.5, 0.8, 1.0, 1.5, 2.0, 3.0]:
    print(f"  ({d}, {power.solve_power(effect_size=d, alpha=0.01, power=0.8):.6f}),")
