#!/usr/bin/env bash
# Opens DIR/report.html in headless Chromium, 1280 px wide, and checks that it loads without
# errors or external resources, that every figure renders with a non-zero size, and that the
# page opens with its answer: the summary, with every claim's verdict, is on the first screen
# (1280 x 800), above the first figure outside it. Keeps a screenshot of that first screen as
# DIR/report.png.
# Usage: bash tests/browser/check_report.sh DIR   (needs Debian's chromium: /usr/bin/chromium)
set -euo pipefail
dir=$(cd "$1" && pwd)
report="$dir/report.html"
[ -s "$report" ] || { echo "check_report: $report is missing or empty" >&2; exit 1; }
# Without a browser the check fails, as it always has (.ci/run installs Debian's chromium).
command -v chromium >/dev/null 2>&1 || { echo "check_report: chromium not found" >&2; exit 127; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# A probe page loads the report in a same-folder iframe of the first screen's size and writes
# its findings into its own DOM, which --dump-dom prints once the page has settled.
cat > "$dir/.report_probe.html" <<'HTML'
<!doctype html><html><head><meta charset="utf-8"><title>probe</title></head><body style="margin:0">
<pre id="result">PENDING</pre>
<iframe id="r" src="report.html" style="width:1280px;height:800px;border:0"></iframe>
<script>
const errors = [];
window.addEventListener('error', e => errors.push(String(e.message)));
document.getElementById('r').addEventListener('load', () => {
  const out = document.getElementById('result');
  try {
    const doc = document.getElementById('r').contentDocument;
    const screen = doc.defaultView.innerHeight;
    const svgs = [...doc.querySelectorAll('figure svg, svg')].filter(s => !s.parentElement.closest('svg'));
    const empty = svgs.filter(s => { const b = s.getBoundingClientRect(); return !(b.width > 0 && b.height > 0); });
    const external = doc.querySelectorAll('script, link[href], img[src], iframe').length;
    const resources = doc.defaultView.performance.getEntriesByType('resource').length;
    const summary = doc.getElementById('summary');
    const verdicts = summary ? [...summary.querySelectorAll('.verdict')] : [];
    const shown = verdicts.filter(v => { const b = v.getBoundingClientRect(); return b.height > 0 && b.bottom <= screen; });
    const later = [...doc.querySelectorAll('section:not(#summary) figure')][0];
    const summaryFirst = summary && (!later || (summary.compareDocumentPosition(later) & Node.DOCUMENT_POSITION_FOLLOWING)) ? 1 : 0;
    const summaryTop = summary ? Math.round(summary.getBoundingClientRect().top) : -1;
    const height = doc.documentElement.scrollHeight;
    out.textContent = `title=${doc.title} figures=${svgs.length} empty=${empty.length} external=${external} resources=${resources} errors=${errors.length}` +
      ` summary_top=${summaryTop} summary_first=${summaryFirst} verdicts=${verdicts.length} verdicts_on_first_screen=${shown.length} page_height=${height}`;
  } catch (e) {
    out.textContent = 'FAILED ' + e;
  }
});
</script></body></html>
HTML
flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run
  --disable-background-networking --disable-component-update --disable-sync --hide-scrollbars
  --user-data-dir="$work/profile")
result=$(timeout 120 chromium "${flags[@]}" --allow-file-access-from-files \
  --virtual-time-budget=10000 --dump-dom "file://$dir/.report_probe.html" 2>/dev/null \
  | sed -n 's:.*<pre id="result">\(.*\)</pre>.*:\1:p')
rm -f "$dir/.report_probe.html"
rm -f "$dir/report.png"
timeout 120 chromium "${flags[@]}" --window-size=1280,800 --screenshot="$dir/report.png" \
  "file://$report" >/dev/null 2>&1 || true
echo "check_report: $result"
field() { echo "$result" | sed -n "s/.* $1=\([0-9-]*\).*/\1/p"; }
case "$result" in
  "title=thermonav report figures="*" empty=0 external=0 resources=0 errors=0 "*)
    figures=$(field figures)
    [ "$figures" -ge 5 ] || { echo "check_report: only $figures figures" >&2; exit 1; }
    verdicts=$(field verdicts)
    [ "$(field summary_first)" = 1 ] && [ "$(field summary_top)" -ge 0 ] && [ "$(field summary_top)" -lt 800 ] \
      || { echo "check_report: the summary does not open the page (on the first 800 px, before the other figures)" >&2; exit 1; }
    [ "$verdicts" -ge 1 ] && [ "$(field verdicts_on_first_screen)" = "$verdicts" ] \
      || { echo "check_report: $(field verdicts_on_first_screen) of $verdicts verdicts on the first screen (1280 x 800)" >&2; exit 1; }
    [ -s "$dir/report.png" ] || { echo "check_report: no screenshot" >&2; exit 1; }
    echo "check_report: ok ($figures figures; the summary's $verdicts verdicts on the first screen, screenshot $dir/report.png)";;
  *) echo "check_report: the report did not load cleanly" >&2; exit 1;;
esac
