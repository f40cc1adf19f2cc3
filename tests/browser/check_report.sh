#!/usr/bin/env bash
# Opens DIR/report.html in headless Chromium and checks that it loads without errors and that
# every figure renders with a non-zero size; saves a screenshot as DIR/report.png.
# Usage: bash tests/browser/check_report.sh DIR   (needs Debian's chromium: /usr/bin/chromium)
set -euo pipefail
dir=$(cd "$1" && pwd)
report="$dir/report.html"
[ -s "$report" ] || { echo "check_report: $report is missing or empty" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# A probe page loads the report in a same-folder iframe and writes its findings into its own
# DOM, which --dump-dom prints once the page has settled.
cat > "$dir/.report_probe.html" <<'HTML'
<!doctype html><html><head><meta charset="utf-8"><title>probe</title></head><body>
<pre id="result">PENDING</pre>
<iframe id="r" src="report.html" style="width:1400px;height:900px"></iframe>
<script>
const errors = [];
window.addEventListener('error', e => errors.push(String(e.message)));
document.getElementById('r').addEventListener('load', () => {
  const out = document.getElementById('result');
  try {
    const doc = document.getElementById('r').contentDocument;
    const svgs = [...doc.querySelectorAll('figure svg, svg')].filter(s => !s.parentElement.closest('svg'));
    const empty = svgs.filter(s => { const b = s.getBoundingClientRect(); return !(b.width > 0 && b.height > 0); });
    const external = doc.querySelectorAll('script, link[href], img[src], iframe').length;
    const resources = doc.defaultView.performance.getEntriesByType('resource').length;
    out.textContent = `title=${doc.title} figures=${svgs.length} empty=${empty.length} external=${external} resources=${resources} errors=${errors.length}`;
  } catch (e) {
    out.textContent = 'FAILED ' + e;
  }
});
</script></body></html>
HTML
flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run
  --disable-background-networking --disable-component-update --disable-sync
  --user-data-dir="$work/profile")
result=$(timeout 120 chromium "${flags[@]}" --allow-file-access-from-files \
  --virtual-time-budget=10000 --dump-dom "file://$dir/.report_probe.html" 2>/dev/null \
  | sed -n 's:.*<pre id="result">\(.*\)</pre>.*:\1:p')
rm -f "$dir/.report_probe.html"
timeout 120 chromium "${flags[@]}" --window-size=1400,5000 --screenshot="$dir/report.png" \
  "file://$report" >/dev/null 2>&1 || true
echo "check_report: $result"
case "$result" in
  "title=thermonav report figures="*" empty=0 external=0 resources=0 errors=0")
    figures=$(echo "$result" | sed 's/.*figures=\([0-9]*\).*/\1/')
    [ "$figures" -ge 5 ] || { echo "check_report: only $figures figures" >&2; exit 1; }
    [ -s "$dir/report.png" ] || { echo "check_report: no screenshot" >&2; exit 1; }
    echo "check_report: ok ($figures figures, screenshot $dir/report.png)";;
  *) echo "check_report: the report did not load cleanly" >&2; exit 1;;
esac
