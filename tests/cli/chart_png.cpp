#include "cli/chart_png.h"

#include <gtest/gtest.h>

#include <string>

#include "cli/cli_test_util.h"

namespace glintlab::cli_test {

nlohmann::json chart_manifest(const std::filesystem::path& png) {
  const std::string d = read_text(png);
  if (d.size() < 8 || d.compare(0, 8, std::string("\x89PNG\r\n\x1a\n", 8)) != 0) return nullptr;
  const std::string key = std::string("glintlab:chart") + '\0';
  std::size_t pos = 8;
  while (pos + 12 <= d.size()) {
    std::size_t n = 0;
    for (int i = 0; i < 4; ++i) n = n << 8 | static_cast<unsigned char>(d[pos + std::size_t(i)]);
    if (pos + 12 + n > d.size()) break;
    const std::string type = d.substr(pos + 4, 4), body = d.substr(pos + 8, n);
    if (type == "tEXt" && body.rfind(key, 0) == 0)
      return nlohmann::json::parse(body.substr(key.size()), nullptr, false);
    pos += 12 + n;
  }
  return nullptr;
}

void expect_labelled_chart(const std::filesystem::path& png, std::size_t axes) {
  const nlohmann::json m = chart_manifest(png);
  ASSERT_TRUE(m.is_object()) << png << ": no chart manifest";
  EXPECT_FALSE(m.value("title", std::string()).empty()) << png;
  ASSERT_TRUE(m["axes"].is_array()) << png;
  ASSERT_EQ(m["axes"].size(), axes) << png;
  for (const nlohmann::json& a : m["axes"]) {
    EXPECT_FALSE(a.value("title", std::string()).empty()) << png;
    for (const char* k : {"xlabel", "ylabel"}) {
      const std::string label = a.value(k, std::string());
      EXPECT_NE(label.find('['), std::string::npos) << png << " " << k << " '" << label << "'";
      EXPECT_NE(label.find(']'), std::string::npos) << png << " " << k << " '" << label << "'";
    }
    // A map's colour bar is its legend.
    EXPECT_TRUE(a.value("legend", false) || (a.value("map", false) && a.value("colorbar", false)))
        << png << ": axes '" << a.value("title", "") << "' has no legend";
    if (a.value("map", false)) {
      EXPECT_TRUE(a.value("colorbar", false)) << png << ": no colour scale";
    }
  }
}

}  // namespace glintlab::cli_test
