// The CPU side of the CUDA build (gpu/): the device-support list, the device check's query set,
// its results folder, and the CPU = GPU comparison — which must fail on results a few per cent
// off and pass on results a couple of ulp off, as a device's would be. No GPU is needed: the
// "device" results here are the CPU batches' own, written by the device check's writer.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <iterator>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/model_registry.h"
#include "core/simd/model_batch.h"
#include "experiments/bench/kemppinen2025_table3_scene.h"
#include "gpu/cpu_comparison.h"
#include "gpu/device_support.h"
#include "gpu/query_set.h"
#include "gpu/results_format.h"

namespace glintlab::gpu {
namespace {

namespace fs = std::filesystem;

TEST(GpuDeviceSupport, ListsEveryBuiltinModelInRegistrationOrder) {
  std::vector<std::string> builtin;
  for (const ModelEntry& m : registered_models()) builtin.emplace_back(m.name);
  std::vector<std::string> listed;
  for (const DeviceSupport& s : kDeviceSupport) listed.emplace_back(s.model);
  EXPECT_EQ(listed, builtin);
  EXPECT_TRUE(has_device_kernels("smooth_ggx"));
  EXPECT_FALSE(has_device_kernels("chermain"));
  EXPECT_FALSE(has_device_kernels("no_such_model"));
}

TEST(GpuQuerySet, IsAPrefixOfALargerSetAndUnitDirections) {
  const QuerySet small = make_query_set(64, kQuerySeed);
  const QuerySet large = make_query_set(256, kQuerySeed);
  for (std::size_t k = 0; k < kQueryLayout.size(); ++k)
    for (std::size_t i = 0; i < small.rows; ++i)
      ASSERT_EQ(small.columns[k][i], large.columns[k][i]) << kQueryLayout[k].name << " row " << i;
  const std::size_t wi_x = query_column_index("wi_x"), wo_x = query_column_index("wo_x");
  for (std::size_t i = 0; i < large.rows; ++i) {
    const auto& c = large.columns;
    EXPECT_NEAR(
        c[wi_x][i] * c[wi_x][i] + c[wi_x + 1][i] * c[wi_x + 1][i] + c[wi_x + 2][i] * c[wi_x + 2][i],
        1.0, 1e-12);
    EXPECT_NEAR(
        c[wo_x][i] * c[wo_x][i] + c[wo_x + 1][i] * c[wo_x + 1][i] + c[wo_x + 2][i] * c[wo_x + 2][i],
        1.0, 1e-12);
    EXPECT_GT(c[wi_x + 2][i], 0.0);
  }
  EXPECT_NE(make_query_set(4, kQuerySeed + 1).columns[wi_x][0], small.columns[wi_x][0]);
}

// The share of the set's rows where `model`'s value is non-zero (CPU batch, scalar, defaults).
double nonzero_share(const char* model) {
  const QuerySet q = make_query_set(2048, kQuerySeed);
  const ModelEntry& m = find_model(model);
  std::vector<simd::Column<double>> query;
  for (const auto& c : q.columns) query.push_back({c.data(), 1});
  std::vector<std::vector<double>> out(2 + m.intermediates.size(), std::vector<double>(q.rows));
  std::vector<double*> outputs;
  for (auto& o : out) outputs.push_back(o.data());
  simd::eval_batch(m, resolve_params(m, {}), query, outputs, q.rows, simd::Isa::kScalar);
  std::size_t nonzero = 0;
  for (double v : out[0]) nonzero += v > 0 ? 1 : 0;
  return double(nonzero) / double(q.rows);
}

// Half the rows sit near the mirror direction: there a smooth lobe is non-zero, so the
// comparison compares values, not zeros.
TEST(GpuQuerySet, MostRowsGiveANonZeroValue) { EXPECT_GT(nonzero_share("smooth_ggx"), 0.5); }

// Podee et al.'s model reads the light's cone and the pixel-corner reflections: on the rows whose
// corners surround ω_o the pixel sees the light, so its value is compared where it is non-zero.
TEST(GpuQuerySet, PodeeSeesTheLightOnAboutHalfTheRows) {
  const double share = nonzero_share("podee");
  EXPECT_GT(share, 0.4);
  EXPECT_LT(share, 0.9);  // the other rows keep the zero branch (the light outside the pixel)
}

// A results folder as the device check writes it, with the CPU batches' results standing in for
// the device's, each value passed through `alter(run, column, row, value)`.
template <class Alter>
fs::path write_folder(const std::string& name, std::size_t rows, const Alter& alter) {
  const fs::path dir = fs::path(::testing::TempDir()) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  const QuerySet q = make_query_set(rows, kQuerySeed);
  write_query_csv(dir / "queries.csv", q, rows);
  std::vector<RunRecord> runs;
  for (const char* model : {"smooth_ggx", "smooth_beckmann"}) {
    const ModelEntry& m = find_model(model);
    const auto run_precision = [&]<class T>(T) {
      std::vector<std::vector<T>> query(q.columns.size(), std::vector<T>(rows));
      std::vector<simd::Column<T>> columns;
      for (std::size_t k = 0; k < q.columns.size(); ++k) {
        for (std::size_t i = 0; i < rows; ++i) query[k][i] = static_cast<T>(q.columns[k][i]);
        columns.push_back({query[k].data(), 1});
      }
      for (const char* function : {"eval", "pdf", "sample"}) {
        const bool sample = std::string(function) == "sample";
        std::vector<std::string> names;
        if (sample) {
          for (auto n : simd::kSampleColumns) names.emplace_back(n);
        } else {
          names = {"value", "pdf"};
          for (const auto& n : m.intermediates) names.emplace_back(n);
        }
        std::vector<std::vector<T>> out(names.size(), std::vector<T>(rows));
        std::vector<T*> outputs;
        for (auto& o : out) outputs.push_back(o.data());
        if (sample) {
          std::vector<T> u1(rows), u2(rows);
          for (std::size_t i = 0; i < rows; ++i) {
            u1[i] = static_cast<T>(q.u1[i]);
            u2[i] = static_cast<T>(q.u2[i]);
          }
          simd::sample_batch(m, resolve_params(m, {}), columns, {u1.data(), 1}, {u2.data(), 1},
                             outputs, rows, simd::Isa::kScalar);
        } else {
          simd::eval_batch(m, resolve_params(m, {}), columns, outputs, rows, simd::Isa::kScalar);
        }
        if (std::string(function) == "pdf") {
          out = {out[1]};
          names = {"pdf"};
        }
        RunRecord run{model, precision_name<T>(), function, names, {}};
        for (std::size_t k = 0; k < out.size(); ++k)
          for (std::size_t i = 0; i < rows; ++i) out[k][i] = alter(run, names[k], i, out[k][i]);
        write_output_csv(dir / output_file_name(run), names, out, rows);
        runs.push_back(run);
      }
    };
    run_precision(float{});
    run_precision(double{});
  }
  // The Table 3 frames: a few pixels of every cell, shaded on the CPU.
  std::vector<Table3FrameRun> frames;
  for (const kemppinen_table3::Cell& cell : kemppinen_table3::cells()) {
    Table3FrameRun f;
    f.cell = kemppinen_table3::cell_name(cell);
    const RunRecord run{f.cell, "double", "frame", {"radiance"}, {}};
    kemppinen_table3::with_cell(cell, [&](const auto& shade) {
      for (std::uint64_t n = 0; n < 8; ++n) {
        f.pixels.push_back(kemppinen_table3::pixel_of(n));
        f.radiance.push_back(alter(run, "radiance", n, shade(f.pixels.back())));
      }
    });
    frames.push_back(std::move(f));
  }
  write_table3_pixels_csv(dir / kTable3PixelsFile, frames);
  write_results_json(dir / "results.json",
                     {"CPU standing in for a device", 0, 0, "none", rows, rows, kQuerySeed, 0},
                     runs, frames);
  return dir;
}

const auto kUnchanged = [](const RunRecord&, const std::string&, std::size_t, auto v) { return v; };

TEST(GpuComparison, TheCpusOwnResultsAreWithinBudgetExactly) {
  const FolderComparison c = compare_with_cpu(write_folder("gpu_same", 512, kUnchanged));
  EXPECT_TRUE(c.within_budget) << describe(c);
  ASSERT_EQ(c.runs.size(), 12u);
  ASSERT_EQ(c.frames.size(), kemppinen_table3::cells().size());
  for (const auto* runs : {&c.runs, &c.frames})
    for (const RunComparison& r : *runs)
      for (const ColumnComparison& col : r.columns) EXPECT_EQ(col.max_relative, 0.0) << col.column;
}

// What a device's math library does: a couple of ulp, everywhere.
TEST(GpuComparison, TwoUlpEverywhereIsWithinBudget) {
  const auto two_ulp = [](const RunRecord&, const std::string& column, std::size_t, auto v) {
    using T = decltype(v);
    if (column == "rejected" || v == 0 || !std::isfinite(v)) return v;
    return std::nextafter(std::nextafter(v, T(INFINITY)), T(INFINITY));
  };
  const FolderComparison c = compare_with_cpu(write_folder("gpu_two_ulp", 512, two_ulp));
  EXPECT_TRUE(c.within_budget) << describe(c);
}

// Near-truth inputs that must be rejected: one column 2 % high in every row; a single row 3 % off;
// a flipped rejection.
TEST(GpuComparison, ResultsAFewPerCentOffAreBeyondBudget) {
  const auto value_high = [](const RunRecord& r, const std::string& column, std::size_t, auto v) {
    using T = decltype(v);
    return r.model == "smooth_beckmann" && r.precision == "double" && r.function == "eval" &&
                   column == "value"
               ? v * T(1.02)
               : v;
  };
  FolderComparison c = compare_with_cpu(write_folder("gpu_value_high", 512, value_high));
  EXPECT_FALSE(c.within_budget);
  std::size_t beyond = 0;
  for (const RunComparison& r : c.runs) {
    beyond += r.within_budget ? 0 : 1;
    if (!r.within_budget) {
      EXPECT_EQ(r.model, "smooth_beckmann");
      EXPECT_EQ(r.function, "eval");
    }
  }
  EXPECT_EQ(beyond, 1u);
  EXPECT_NE(describe(c).find("BEYOND"), std::string::npos);

  const auto one_row = [](const RunRecord& r, const std::string& column, std::size_t i, auto v) {
    using T = decltype(v);
    return r.model == "smooth_ggx" && r.precision == "float" && r.function == "pdf" && i == 10 &&
                   column == "pdf"
               ? v * T(1.03)
               : v;
  };
  c = compare_with_cpu(write_folder("gpu_one_row", 512, one_row));
  EXPECT_FALSE(c.within_budget);
  for (const RunComparison& r : c.runs)
    if (!r.within_budget) {
      EXPECT_EQ(r.columns[0].worst_row, 10u);
      EXPECT_EQ(r.columns[0].rows_over, 1u);
      EXPECT_NEAR(r.columns[0].max_relative, 0.03, 1e-6);
    }

  // One Table 3 frame pixel 3 % off.
  const auto frame_pixel = [](const RunRecord& r, const std::string&, std::size_t i, auto v) {
    using T = decltype(v);
    return r.function == "frame" &&
                   r.model == "table3/ndf:ggx/plane:90/roughness:high/model:smooth" && i == 5
               ? v * T(1.03)
               : v;
  };
  c = compare_with_cpu(write_folder("gpu_frame_pixel", 32, frame_pixel));
  EXPECT_FALSE(c.within_budget);
  for (const RunComparison& r : c.runs) EXPECT_TRUE(r.within_budget) << r.model;
  std::size_t frames_beyond = 0;
  for (const RunComparison& r : c.frames) frames_beyond += r.within_budget ? 0 : 1;
  EXPECT_EQ(frames_beyond, 1u);

  const auto flipped = [](const RunRecord& r, const std::string& column, std::size_t i, auto v) {
    using T = decltype(v);
    return r.function == "sample" && column == "rejected" && i == 3 ? T(1) - v : v;
  };
  EXPECT_FALSE(compare_with_cpu(write_folder("gpu_flipped", 64, flipped)).within_budget);
}

TEST(GpuComparison, AMalformedFolderIsNamed) {
  const fs::path dir = write_folder("gpu_malformed", 32, kUnchanged);
  const auto message = [&] {
    try {
      compare_with_cpu(dir);
    } catch (const ResultsError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  fs::remove(dir / "smooth_beckmann.double.sample.csv");
  EXPECT_NE(message().find("smooth_beckmann.double.sample.csv: cannot be read"), std::string::npos)
      << message();
  { std::ofstream(dir / "smooth_beckmann.double.sample.csv") << "wo_x,wo_y\n1,2\n"; }
  EXPECT_NE(message().find("2 columns, the CPU batch writes 6"), std::string::npos) << message();
  { std::ofstream(dir / "queries.csv") << "u,v\n0.5,x\n"; }
  EXPECT_NE(message().find("queries.csv: row 1, column 'v' is not a number"), std::string::npos)
      << message();
  fs::remove(dir / "results.json");
  EXPECT_NE(message().find("results.json: cannot be read"), std::string::npos) << message();
}

// The report's GPU section reads the folder the device check writes (gpu/results_format.cpp):
// a folder written by that writer, in a report's gpu/ part, gives one rate row per model and
// precision and one row per Table 3 cell; the same folder with a field gone is a one-line error.
TEST(GpuResultsFolder, TheReportShowsWhatTheDeviceCheckWrites) {
  const fs::path folder = write_folder("gpu_for_report", 16, kUnchanged);
  const fs::path stage = fs::path(::testing::TempDir()) / "gpu_report_stage";
  fs::remove_all(stage);
  fs::create_directories(stage);
  fs::copy(folder, stage / "gpu", fs::copy_options::recursive);
  const std::string make = std::string("/usr/bin/python3 ") + GLINTLAB_SOURCE_DIR +
                           "/reports/make_report.py --dir " + stage.string() + " > " +
                           (stage.parent_path() / "gpu_report.log").string() + " 2>&1";
  ASSERT_EQ(std::system(make.c_str()), 0);
  std::ifstream in(stage / "report.md");
  const std::string md((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("Models on a GPU"), std::string::npos);
  EXPECT_NE(md.find("CPU standing in for a device"), std::string::npos);
  for (const char* row : {"| smooth_ggx | float |", "| smooth_ggx | double |",
                          "| smooth_beckmann | float |", "| smooth_beckmann | double |"})
    EXPECT_NE(md.find(row), std::string::npos) << row;
  for (const kemppinen_table3::Cell& cell : kemppinen_table3::cells())
    EXPECT_NE(md.find("| " + kemppinen_table3::cell_name(cell) + " |"), std::string::npos)
        << kemppinen_table3::cell_name(cell);

  std::ifstream json_in(stage / "gpu" / "results.json");
  std::string json((std::istreambuf_iterator<char>(json_in)), std::istreambuf_iterator<char>());
  json_in.close();
  const std::size_t at = json.find("\"rows_per_second\"");
  ASSERT_NE(at, std::string::npos);
  json.replace(at, std::string("\"rows_per_second\"").size(), "\"rows_per_sec\"");
  { std::ofstream(stage / "gpu" / "results.json") << json; }
  fs::remove(stage / "report.md");
  fs::remove(stage / "index.html");
  EXPECT_EQ(WEXITSTATUS(std::system(make.c_str())), 2);
  EXPECT_FALSE(fs::exists(stage / "report.md"));
  std::ifstream log(stage.parent_path() / "gpu_report.log");
  const std::string err((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_NE(err.find("glintlab: error: report: gpu/results.json is malformed: runs[0] has no "
                     "valid \"rows_per_second\""),
            std::string::npos)
      << err;
}

}  // namespace
}  // namespace glintlab::gpu
