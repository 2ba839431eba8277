#include "report/page.hpp"

#include "report/html.hpp"

namespace sgnlf::report {
namespace {

constexpr const char* kStyle = R"(
body{font-family:system-ui,sans-serif;margin:1.5em auto;max-width:1100px;padding:0 1em;color:#222}
h1{font-size:1.5em}h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:1.6em}
table{border-collapse:collapse;margin:.6em 0;font-size:.9em}
th,td{border:1px solid #ddd;padding:.25em .6em;vertical-align:top}
th{background:#f4f4f4}table.num td{text-align:right}table.num td:first-child{text-align:left}
table.kv td:first-child{font-weight:600}
.better{color:#1a7f37;font-weight:600}.worse{color:#b42318}
.note{color:#666;font-style:italic}small{color:#777}
pre{background:#f7f7f7;padding:.6em;overflow:auto;max-height:30em;font-size:.8em}
figure{margin:.6em 0}figure img{max-width:100%;border:1px solid #ddd}
figcaption{font-size:.85em;color:#555}.charts{display:flex;flex-wrap:wrap;gap:.5em}
.charts svg{border:1px solid #eee}
.pair{position:relative;display:inline-block;max-width:100%}
.tag{position:absolute;left:6px;background:rgba(255,255,255,.85);padding:0 .4em;font-size:.85em;font-weight:600}
.tag.top{top:6px}.tag.bottom{top:calc(50% + 6px)}
nav a{margin-right:1em}#sgnlf-image-check{font-size:.8em;color:#666}
#sgnlf-image-check.bad{color:#b42318;font-weight:600}
)";

// Runs on load; ES5 and no "</" inside, so that it cannot close its own element.
constexpr const char* kImageCheck = R"(
window.addEventListener('load', function () {
  var im = document.images, ok = 0;
  for (var i = 0; i < im.length; i++) {
    if (im[i].complete && im[i].naturalWidth > 0) ok++;
    else console.error('sgnlf report: picture ' + i + ' (' + im[i].alt + ') did not load');
  }
  var m = document.getElementById('sgnlf-image-check');
  m.setAttribute('data-images', ok + '/' + im.length);
  m.className = ok === im.length ? 'ok' : 'bad';
  m.textContent = 'pictures decoded: ' + ok + ' of ' + im.length;
});
)";

}  // namespace

std::string html_page(const std::string& title, const std::string& body) {
  std::string o = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  o += "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; "
       "style-src 'unsafe-inline'; script-src 'unsafe-inline'\">\n";
  o += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  o += "<title>" + escape(title) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n";
  o += body;
  o += "<footer><p id=\"sgnlf-image-check\" data-images=\"\">pictures: not checked (scripts "
       "off)</p><p class=\"note\">Written by <code>sgnlf report</code>; self-contained, loads "
       "nothing.</p></footer>\n";
  o += std::string("<script>") + kImageCheck + "</script>\n</body>\n</html>\n";
  return o;
}

}  // namespace sgnlf::report
