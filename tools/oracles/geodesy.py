"""Oracle values for geodetic <-> ECEF <-> NED conversions, from pymap3d (an independent
implementation). Run once: python3 tools/oracles/geodesy.py > crates/thermonav/tests/data/geodesy.json
Made with pymap3d 3.x, numpy; WGS84 ellipsoid."""
import json
import pymap3d as pm

points = [(0.0, 0.0, 0.0), (51.08, -114.13, 1100.0), (-33.9, 151.2, 45.0), (89.9, 10.0, -30.0),
          (45.0, 179.9, 20000.0), (-70.0, -60.0, 3000.0)]
cases = []
for lat, lon, h in points:
    x, y, z = pm.geodetic2ecef(lat, lon, h)
    cases.append({"lat_deg": lat, "lon_deg": lon, "h_m": h, "ecef_m": [x, y, z]})
origin = (51.08, -114.13, 1100.0)
displacements = []
for lat, lon, h in [(51.081, -114.128, 1105.0), (51.0, -114.3, 1000.0), (51.2, -113.9, 1500.0)]:
    n, e, d = pm.geodetic2ned(lat, lon, h, *origin)
    displacements.append({"lat_deg": lat, "lon_deg": lon, "h_m": h, "ned_m": [n, e, d]})
print(json.dumps({"source": f"pymap3d {pm.__version__}", "origin": origin, "ecef": cases,
                  "ned_from_origin": displacements}, indent=1))
