#include "sim/cli/compare_page_style.hpp"

namespace bimloc::cli {

const char* const kComparePageStyle = R"css(
:root { --ink: #1f2328; --muted: #656d76; --line: #d0d7de; --soft: #f6f8fa; --best: #dafbe1; --best-ink: #116329;
        --bad: #cf222e; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--ink); background: #fff; line-height: 1.5;
       font: 15px/1.5 system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif; }
main { max-width: 1100px; margin: 0 auto; padding: 24px 24px 48px; }
h1 { font-size: 26px; margin: 0 0 4px; }
h2 { font-size: 19px; margin: 36px 0 8px; padding-bottom: 4px; border-bottom: 1px solid var(--line); }
.sub, .note, figcaption, .muted { color: var(--muted); }
.sub { margin: 0 0 18px; }
.verdict { border-left: 5px solid var(--best-ink); background: var(--best); padding: 12px 16px; border-radius: 6px;
           font-size: 16px; }
.verdict b { color: var(--best-ink); }
table { border-collapse: collapse; margin: 8px 0; font-variant-numeric: tabular-nums; }
th, td { padding: 5px 12px; border-bottom: 1px solid var(--line); text-align: right; white-space: nowrap; }
th { background: var(--soft); font-weight: 600; }
th:first-child, td:first-child { text-align: left; }
td.best { background: var(--best); color: var(--best-ink); font-weight: 700; }
td.best a { color: var(--best-ink); }
ul.methods { list-style: none; padding: 0; margin: 6px 0; color: var(--muted); font-size: 14px; }
ul.methods b { color: var(--ink); }
.swatch { display: inline-block; width: 11px; height: 11px; border-radius: 2px; margin-right: 7px; vertical-align: 0; }
.badge { display: inline-block; margin-left: 8px; padding: 0 7px; border-radius: 9px; font-size: 12px; font-weight: 700;
         background: var(--best-ink); color: #fff; }
.nl { color: var(--muted); }
.false { color: var(--bad); font-weight: 700; }
a { color: #0969da; text-decoration: none; }
a:hover { text-decoration: underline; }
figure { margin: 12px 0; }
figure img { width: 100%; max-width: 1100px; border: 1px solid var(--line); border-radius: 4px; }
details { border: 1px solid var(--line); border-radius: 6px; margin: 6px 0; padding: 4px 12px; }
details[open] { padding-bottom: 12px; }
summary { cursor: pointer; font-weight: 600; }
summary span { font-weight: 400; color: var(--muted); }
.method { margin-top: 10px; padding: 6px 8px; border-radius: 6px; }
.method:target { outline: 3px solid #0969da; }
.method h3 { font-size: 15px; margin: 0 0 6px; }
.strip { display: flex; flex-wrap: wrap; gap: 8px; }
.strip a { display: block; text-align: center; font-size: 12px; color: var(--muted); }
.strip img { display: block; width: 188px; height: 141px; object-fit: contain; border: 1px solid var(--line);
             border-radius: 4px; background: var(--soft); }
footer { margin-top: 36px; font-size: 13px; color: var(--muted); }
)css";

const char* const kComparePageScript = R"js(
window.addEventListener('load', function () {
  var images = Array.prototype.slice.call(document.images), loaded = 0, settled = 0;
  function mark() { document.body.dataset.images = loaded + '/' + images.length; }
  if (images.length === 0) mark();
  images.forEach(function (image) {
    var probe = new Image();
    probe.onload = function () { if (probe.naturalWidth > 0) loaded++; if (++settled === images.length) mark(); };
    probe.onerror = function () { if (++settled === images.length) mark(); };
    probe.src = image.src;
  });
});
function unfold() {
  var target = location.hash && document.getElementById(decodeURIComponent(location.hash.slice(1)));
  for (var e = target; e; e = e.parentElement) if (e.tagName === 'DETAILS') e.open = true;
  if (target) target.scrollIntoView();
}
window.addEventListener('hashchange', unfold);
window.addEventListener('DOMContentLoaded', unfold);
)js";

}  // namespace bimloc::cli
