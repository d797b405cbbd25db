#include "post/html_page.h"

#include <cctype>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "model/io/output_file.h"

namespace turbodyn::post {
namespace {

// Style: readable on screen and on paper, pictures at most the page's width.
constexpr const char* kStyle = R"(
body{font-family:sans-serif;max-width:1100px;margin:1.5em auto;padding:0 1em;color:#202020;line-height:1.4}
h1{font-size:1.5em;margin-bottom:.2em}h2{font-size:1.2em;margin-top:1.6em;border-bottom:1px solid #ccc}
code,pre{background:#f3f3f3;padding:.1em .3em;border-radius:3px}
pre{padding:.5em;white-space:pre-wrap;word-break:break-all}
.wide{overflow-x:auto}table{border-collapse:collapse;margin:.5em 0}th,td{border:1px solid #d0d0d0;padding:.2em .6em;text-align:left}
th{background:#f0f0f0}.num{white-space:nowrap;font-variant-numeric:tabular-nums}
.warn{background:#fff3e0;border-left:4px solid #e65100;padding:.5em .8em;margin:.6em 0}
.ok{color:#1b5e20}.bad{color:#b71c1c;font-weight:bold}
figure{margin:1em 0}figure img{max-width:100%;height:auto;border:1px solid #e0e0e0}
figcaption{font-size:.9em;color:#555}.kind{color:#666;font-size:.9em}
)";

// Marks <body> once the page and its pictures have loaded (see html_page.h).
constexpr const char* kScript = R"(
addEventListener('load', function () {
  var ok = 0, bad = [], im = document.images;
  for (var i = 0; i < im.length; i++) {
    if (im[i].complete && im[i].naturalWidth > 0) ok++;
    else bad.push(im[i].getAttribute('src'));
  }
  var b = document.body.dataset;
  b.imagesTotal = im.length; b.imagesLoaded = ok; b.imagesBroken = bad.join(' '); b.rendered = 'yes';
});
)";

// A file name as a relative URL: characters outside the unreserved set percent-encoded.
std::string url_of(const std::string& name) {
  std::string out;
  for (unsigned char c : name) {
    if (std::isalnum(c) || c == '.' || c == '-' || c == '_' || c == '~') {
      out += static_cast<char>(c);
    } else {
      const char* hex = "0123456789ABCDEF";
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

std::string escape_pointer_token(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

}  // namespace

std::string html_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string display_number(double v, int digits) {
  if (!std::isfinite(v)) return "–";
  if (v == 0.0) return "0";
  std::ostringstream os;
  const double a = std::abs(v);
  if (a >= 1e-3 && a < 1e7) {
    const int magnitude = static_cast<int>(std::floor(std::log10(a)));
    os << std::fixed << std::setprecision(std::max(0, digits - 1 - magnitude)) << v;
  } else {
    os << std::scientific << std::setprecision(digits - 1) << v;
  }
  return os.str();
}

std::string json_pointer(const std::string& parent, const std::string& key) {
  return parent + "/" + escape_pointer_token(key);
}

std::string json_pointer(const std::string& parent, std::size_t index) {
  return parent + "/" + std::to_string(index);
}

HtmlPage::HtmlPage(std::string title, std::string kind) : title_(std::move(title)), kind_(std::move(kind)) {}

void HtmlPage::heading(const std::string& text) { body_ += "<h2>" + html_escape(text) + "</h2>\n"; }

void HtmlPage::paragraph(const std::string& text) { body_ += "<p>" + html_escape(text) + "</p>\n"; }

void HtmlPage::paragraph_html(const std::string& html) { body_ += "<p>" + html + "</p>\n"; }

void HtmlPage::command(const std::string& text) { body_ += "<pre>" + html_escape(text) + "</pre>\n"; }

void HtmlPage::alert(const std::string& text) {
  body_ += "<div class=\"warn\" data-alert>" + html_escape(text) + "</div>\n";
}

void HtmlPage::warnings(const std::vector<std::string>& list) {
  if (list.empty()) return;
  body_ += "<div class=\"warn\"><strong>Warnings</strong><ul data-warnings>\n";
  for (const std::string& w : list) body_ += "<li>" + html_escape(w) + "</li>\n";
  body_ += "</ul></div>\n";
}

void HtmlPage::table(const std::string& label, const std::vector<std::string>& header,
                     const std::vector<std::vector<std::string>>& rows) {
  // A study's table can be wider than the page: it scrolls sideways, the page does not.
  body_ += "<div class=\"wide\"><table data-table=\"" + html_escape(label) + "\">\n<tr>";
  for (const std::string& h : header) body_ += "<th>" + html_escape(h) + "</th>";
  body_ += "</tr>\n";
  for (const auto& row : rows) {
    body_ += "<tr>";
    for (const std::string& cell : row) body_ += "<td>" + cell + "</td>";
    body_ += "</tr>\n";
  }
  body_ += "</table></div>\n";
}

void HtmlPage::key_values(const std::string& label, const std::vector<std::pair<std::string, std::string>>& rows) {
  body_ += "<table data-table=\"" + html_escape(label) + "\">\n";
  for (const auto& [k, v] : rows) body_ += "<tr><th>" + html_escape(k) + "</th><td>" + v + "</td></tr>\n";
  body_ += "</table>\n";
}

void HtmlPage::pictures(const std::vector<std::string>& files) {
  if (files.empty()) {
    body_ += "<p>No pictures (drawn with gnuplot; none were asked for, or none could be drawn).</p>\n";
    return;
  }
  for (const std::string& f : files) {
    const std::string url = html_escape(url_of(f)), name = html_escape(f);
    body_ += "<figure><a href=\"" + url + "\"><img src=\"" + url + "\" alt=\"" + name + "\"></a><figcaption>" + name +
             "</figcaption></figure>\n";
  }
}

void HtmlPage::files(const std::vector<std::string>& names) {
  if (names.empty()) return;
  body_ += "<ul data-files>\n";
  for (const std::string& f : names)
    body_ += "<li><a href=\"" + html_escape(url_of(f)) + "\">" + html_escape(f) + "</a></li>\n";
  body_ += "</ul>\n";
}

std::string HtmlPage::number(const std::string& file, const nlohmann::json& root, const std::string& pointer,
                             double scale, const std::string& unit, int digits) {
  const nlohmann::json::json_pointer ptr(pointer);
  if (!root.contains(ptr) || !root.at(ptr).is_number()) return "–";
  const nlohmann::json& v = root.at(ptr);
  std::ostringstream sc;
  sc << std::setprecision(17) << scale;
  return "<span class=\"num\" data-file=\"" + html_escape(file) + "\" data-pointer=\"" + html_escape(pointer) +
         "\" data-value=\"" + v.dump() + "\" data-scale=\"" + sc.str() + "\" data-digits=\"" +
         std::to_string(digits) + "\">" +
         (v.is_number_integer() && scale == 1.0 ? v.dump() : display_number(v.get<double>() * scale, digits)) +
         (unit.empty() ? "" : " " + html_escape(unit)) + "</span>";
}

std::string HtmlPage::html() const {
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" +
         html_escape(title_) + "</title>\n<style>\n" + kStyle + "\n</style>\n</head>\n<body data-kind=\"" +
         html_escape(kind_) + "\">\n<h1>" + html_escape(title_) + "</h1>\n<p class=\"kind\">turbodyn " +
         html_escape(kind_) + " report</p>\n" + body_ + "<script>" + kScript + "</script>\n</body>\n</html>\n";
}

void HtmlPage::write(const std::filesystem::path& dir) const { write_output_file(dir / "report.html", html()); }

}  // namespace turbodyn::post
