// report.html pieces: escaping, numbers shown as engineers read them and tied to their source in the result file,
// a page without external references.
#include "post/html_page.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace turbodyn::post {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(HtmlPage, TextIsEscaped) {
  EXPECT_EQ(html_escape("<b>\"a\" & 'b'</b>"), "&lt;b&gt;&quot;a&quot; &amp; &#39;b&#39;&lt;/b&gt;");
  HtmlPage page("Rotor <script>alert(1)</script>", "run");
  page.paragraph("a < b & c");
  page.warnings({"<img src=x onerror=alert(1)>"});
  const std::string html = page.html();
  EXPECT_THAT(html, Not(HasSubstr("<script>alert")));
  EXPECT_THAT(html, Not(HasSubstr("<img src=x")));
  EXPECT_THAT(html, HasSubstr("a &lt; b &amp; c"));
}

TEST(HtmlPage, NumbersAreShownToTheirDigits) {
  EXPECT_EQ(display_number(283.04), "283.0");
  EXPECT_EQ(display_number(150000.0, 5), "150000");
  EXPECT_EQ(display_number(0.048712), "0.04871");
  EXPECT_EQ(display_number(2.83e-7), "2.830e-07");
  EXPECT_EQ(display_number(-1.5e9, 3), "-1.50e+09");
  EXPECT_EQ(display_number(0.0), "0");
  EXPECT_EQ(display_number(NAN), "–");
}

TEST(HtmlPage, ANumberCarriesItsFileAndPointer) {
  const nlohmann::json j = {{"probes", {{"disk/x", {{"max_abs", 0.000283}}}}}, {"steps", 46248}, {"none", nullptr}};
  const std::string ptr = json_pointer(json_pointer("/probes", "disk/x"), "max_abs");
  EXPECT_EQ(ptr, "/probes/disk~1x/max_abs");
  const std::string n = HtmlPage::number("summary.json", j, ptr, 1e6, "µm");
  EXPECT_THAT(n, HasSubstr("data-file=\"summary.json\""));
  EXPECT_THAT(n, HasSubstr("data-pointer=\"/probes/disk~1x/max_abs\""));
  EXPECT_THAT(n, HasSubstr("data-value=\"0.000283\""));
  EXPECT_THAT(n, HasSubstr(">283.0 µm</span>"));
  EXPECT_THAT(HtmlPage::number("summary.json", j, "/steps"), HasSubstr(">46248</span>"));
  EXPECT_EQ(HtmlPage::number("summary.json", j, "/none"), "–");
  EXPECT_EQ(HtmlPage::number("summary.json", j, "/missing"), "–");
}

TEST(HtmlPage, PicturesAndFilesAreRelativeLinksAndThePageHasNoExternalReference) {
  HtmlPage page("t", "run");
  page.pictures({"spectrogram_disk.x.png", "a b.png"});
  page.files({"summary.json"});
  const std::string html = page.html();
  EXPECT_THAT(html, HasSubstr("<img src=\"spectrogram_disk.x.png\""));
  EXPECT_THAT(html, HasSubstr("<img src=\"a%20b.png\""));
  EXPECT_THAT(html, HasSubstr("<a href=\"summary.json\">"));
  EXPECT_THAT(html, Not(HasSubstr("http")));
  EXPECT_THAT(html, Not(HasSubstr("<script src")));
  EXPECT_THAT(html, HasSubstr("data-kind=\"run\""));
}

}  // namespace
}  // namespace turbodyn::post
