// SPDX-License-Identifier: MIT
// history.csv, summary.json, the step data and the progress text, checked piece by piece.
#include "io/atomic_file.hpp"
#include "io/case_runner.hpp"
#include "io/history.hpp"
#include "io/progress.hpp"
#include "io/step_output.hpp"
#include "mesh/error.hpp"

#include "../../support/case_fixtures.hpp"
#include "../../support/json_reader.hpp"
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace nmm {
namespace {

using testing::parse_json;
using testing::read_text;
using testing::TempDir;

// ---------------------------------------------------------------------------------------
// history.csv

TEST(History, HeaderHasTheContractColumnsThenNineColumnsPerMonitorThenTheWorkOfTheLoads) {
  const std::vector<std::string> monitors{"crest", "toe"};
  EXPECT_EQ(history_header(monitors),
            "step,time,dt,open_close_iterations,contacts,kinetic_energy,"
            "crest.x,crest.y,crest.ux,crest.uy,crest.vx,crest.vy,crest.sxx,crest.syy,crest.sxy,"
            "toe.x,toe.y,toe.ux,toe.uy,toe.vx,toe.vy,toe.sxx,toe.syy,toe.sxy,load_work,step_cuts,"
            "max_penetration,lock_excess,slide_feed"
            ",external_work,strain_energy,contact_energy,dissipated_energy,energy_error");
  EXPECT_EQ(history_header({}),
            "step,time,dt,open_close_iterations,contacts,kinetic_energy,load_"
            "work,step_cuts,max_penetration,lock_excess,slide_feed"
            ",external_work,strain_energy,contact_energy,dissipated_energy,energy_error");
}

TEST(History, EveryRowIsOnDiskAtOnceAndRealsReadBackBitForBit) {
  const TempDir dir("nmm_history");
  const auto file = dir.path() / "history.csv";
  HistoryWriter history(file, {"m"});
  StepReport report;
  report.step = 7;
  report.time = 0.1 + 0.2; // not representable in fewer than 17 digits
  report.dt = 1.0 / 3.0;
  report.open_close_iterations = 2;
  report.contacts = 5;
  report.kinetic_energy = 1.0e-300;
  report.load_work = -0.1;
  report.step_cuts = 3;
  report.max_penetration = 2.5e-7;
  report.lock_excess = 1.0 + 1.0 / 3.0;
  report.slide_feed = 0.1 + 0.7;
  report.external_work = 1.0 / 7.0;
  report.strain_energy = -2.0 / 3.0;
  report.contact_energy = 0.3;
  report.dissipated_energy = 1.0e-17;
  report.energy_error = 0.1 + 0.4;
  MonitorValues m;
  m.x = std::numbers::pi;
  m.sxy = -2.5e9;
  const std::vector<MonitorValues> monitors{m};
  history.write_row(report, monitors);
  // Read while the writer is still open: the row was flushed.
  std::istringstream lines(read_text(file));
  std::string header;
  std::string row;
  std::getline(lines, header);
  std::getline(lines, row);
  EXPECT_EQ(header, history_header(std::vector<std::string>{"m"}));
  std::vector<std::string> fields;
  std::istringstream cells(row);
  for (std::string cell; std::getline(cells, cell, ',');)
    fields.push_back(cell);
  ASSERT_EQ(fields.size(), 6u + 9u + 10u);
  EXPECT_EQ(std::stod(fields[15]), -0.1);
  EXPECT_EQ(fields[16], "3");
  EXPECT_EQ(std::stod(fields[17]), 2.5e-7);
  EXPECT_EQ(std::stod(fields[18]), 1.0 + 1.0 / 3.0);
  EXPECT_EQ(std::stod(fields[19]), 0.1 + 0.7);
  EXPECT_EQ(std::stod(fields[20]), 1.0 / 7.0);
  EXPECT_EQ(std::stod(fields[21]), -2.0 / 3.0);
  EXPECT_EQ(std::stod(fields[22]), 0.3);
  EXPECT_EQ(std::stod(fields[23]), 1.0e-17);
  EXPECT_EQ(std::stod(fields[24]), 0.1 + 0.4);
  EXPECT_EQ(fields[0], "7");
  EXPECT_EQ(std::stod(fields[1]), 0.1 + 0.2);
  EXPECT_EQ(std::stod(fields[2]), 1.0 / 3.0);
  EXPECT_EQ(fields[3], "2");
  EXPECT_EQ(fields[4], "5");
  EXPECT_EQ(std::stod(fields[5]), 1.0e-300);
  EXPECT_EQ(std::stod(fields[6]), std::numbers::pi);
  EXPECT_EQ(std::stod(fields[14]), -2.5e9);
}

TEST(History, RealsOfTheLongestTextReadBackWhole) {
  // -1.2345678901234567e-305 is the longest text %.17g writes (24 characters): a row of
  // them in every real column reads back bit for bit, none cut.
  const TempDir dir("nmm_history_long");
  const auto file = dir.path() / "history.csv";
  HistoryWriter history(file, {"m"});
  const double longest = -1.2345678901234567e-305;
  StepReport report;
  report.step = 123456789;
  report.time = report.dt = report.kinetic_energy = report.load_work = longest;
  report.max_penetration = report.lock_excess = report.slide_feed = longest;
  report.external_work = report.strain_energy = report.contact_energy = longest;
  report.dissipated_energy = report.energy_error = longest;
  report.open_close_iterations = report.contacts = report.step_cuts = 2147483647;
  MonitorValues m;
  m.x = m.y = m.ux = m.uy = m.vx = m.vy = m.sxx = m.syy = m.sxy = longest;
  history.write_row(report, std::vector<MonitorValues>{m});
  std::istringstream lines(read_text(file));
  std::string row;
  std::getline(lines, row);
  std::getline(lines, row);
  std::vector<std::string> fields;
  std::istringstream cells(row);
  for (std::string cell; std::getline(cells, cell, ',');)
    fields.push_back(cell);
  ASSERT_EQ(fields.size(), 6u + 9u + 10u);
  for (const std::size_t i : {1, 2, 5, 6, 14, 15, 17, 18, 19, 20, 21, 22, 23, 24}) {
    EXPECT_EQ(fields[i].size(), 24u) << "column " << i;
    EXPECT_EQ(std::stod(fields[i]), longest) << "column " << i;
  }
  EXPECT_EQ(fields[0], "123456789");
  EXPECT_EQ(fields[16], "2147483647");
}

TEST(History, RowCutShortByAFileSizeLimitIsTakenBackAndTheErrorSaysWhy) {
  // A file-size limit (ulimit -f) of the header and two and a half rows: the third row is
  // cut by the kernel part way. It must leave the file as it was after the second row.
  const TempDir dir("nmm_history");
  const auto file = dir.path() / "history.csv";
  StepReport report;
  report.time = 0.1 + 0.2;
  report.dt = 1.0 / 3.0;
  const std::vector<MonitorValues> monitors{MonitorValues{}};
  std::string expected;
  {
    HistoryWriter reference(dir.path() / "reference.csv", {"m"});
    for (report.step = 1; report.step <= 3; ++report.step)
      reference.write_row(report, monitors);
    expected = read_text(dir.path() / "reference.csv");
  }
  const std::size_t row =
      (expected.size() - history_header(std::vector<std::string>{"m"}).size() - 1) / 3;
  const std::size_t two_rows = expected.size() - row;
  struct rlimit saved {};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN); // as nmm does (io/cli.cpp)
  struct rlimit limit = saved;
  limit.rlim_cur = static_cast<rlim_t>(two_rows + row / 2);
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &limit), 0);
  std::string message;
  {
    HistoryWriter history(file, {"m"});
    try {
      for (report.step = 1; report.step <= 3; ++report.step)
        history.write_row(report, monitors);
    } catch (const OutputWriteError& error) {
      message = error.what();
    }
    EXPECT_EQ(history.bytes(), two_rows);
  }
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &saved), 0);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_EQ(read_text(file), expected.substr(0, two_rows)) << "the cut row is taken back";
  EXPECT_NE(message.find("file too large: cannot write the row of step 3 (the rows before it "
                         "stay) to '" +
                         file.string() + "' (File too large)"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("file-size limit of " + std::to_string(two_rows + row / 2) + " bytes"),
            std::string::npos)
      << message;
}

TEST(History, UnwritableFileIsAnInputErrorNamingIt) {
  const TempDir dir("nmm_history");
  testing::write_text(dir.path() / "file", "x");
  const auto file = dir.path() / "file" / "history.csv"; // a file as parent folder
  try {
    HistoryWriter history(file, {});
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(file.string()), std::string::npos) << error.what();
  }
}

// ---------------------------------------------------------------------------------------
// summary.json

TEST(Json, StringsAreEscapedAsJsonRequires) {
  EXPECT_EQ(json_string("plain"), "\"plain\"");
  EXPECT_EQ(json_string("a \"b\" \\ c"), R"("a \"b\" \\ c")");
  EXPECT_EQ(json_string("line\nnext\ttab"), R"("line\nnext\ttab")");
  EXPECT_EQ(json_string(std::string("\x01", 1)), R"("\u0001")");
  EXPECT_EQ(json_string("m³ und Ü"), "\"m³ und Ü\""); // UTF-8 passes through
  const std::string nasty = "case.toml:3: \"x\"\\y\n\x1f";
  EXPECT_EQ(parse_json(json_string(nasty)).string, nasty);
}

TEST(Json, NumbersRoundTripAndNonFiniteBecomesNull) {
  EXPECT_EQ(std::stod(json_number(0.1 + 0.2)), 0.1 + 0.2);
  EXPECT_EQ(json_number(std::numeric_limits<double>::quiet_NaN()), "null");
  EXPECT_EQ(json_number(-std::numeric_limits<double>::infinity()), "null");
  EXPECT_EQ(json_number(2.0), "2");
}

TEST(Json, SummaryIsValidJsonWithTheContractKeysFirst) {
  RunSummary s;
  s.status = "numerical failure: \"x\"";
  s.steps = 12;
  s.time = 0.5;
  s.wall_seconds = 1.25;
  s.dofs = 100;
  s.covers = 50;
  s.elements = 80;
  s.blocks = 2;
  s.warnings = {"case.toml:3: a \"quoted\" warning", "second"};
  MonitorValues crest;
  crest.uy = -0.125;
  crest.sxx = std::numeric_limits<double>::quiet_NaN();
  s.monitors = {{"crest", crest}, {"toe", MonitorValues{}}};
  s.counters.steps = 12;
  s.solver_counters.factorizations = 13;
  s.mesher.cut_triangles = 4;
  s.max_penetration = 2.5e-7;
  const testing::Json json = parse_json(summary_json(s));
  ASSERT_TRUE(json.is_object());
  const std::vector<std::string> contract{"status",   "steps",   "time",     "wall_seconds",
                                          "dofs",     "covers",  "elements", "blocks",
                                          "warnings", "monitors"};
  const std::vector<std::string> keys = json.keys();
  ASSERT_GE(keys.size(), contract.size());
  EXPECT_EQ(std::vector<std::string>(keys.begin(), keys.begin() + 10), contract);
  EXPECT_EQ(json.at("status").string, s.status);
  EXPECT_EQ(json.at("steps").number, 12);
  EXPECT_EQ(json.at("blocks").number, 2);
  ASSERT_EQ(json.at("warnings").items.size(), 2u);
  EXPECT_EQ(json.at("warnings").items[0].string, s.warnings[0]);
  const testing::Json& monitor = json.at("monitors").at("crest");
  std::vector<std::string> names(monitor_value_names.begin(), monitor_value_names.end());
  EXPECT_EQ(monitor.keys(), names);
  EXPECT_EQ(monitor.at("uy").number, -0.125);
  EXPECT_EQ(monitor.at("sxx").kind, testing::Json::Kind::null);
  EXPECT_TRUE(json.at("monitors").at("toe").is_object());
  EXPECT_EQ(json.at("counters").at("factorizations").number, 13);
  EXPECT_EQ(json.at("mesher").at("cut_triangles").number, 4);
  EXPECT_EQ(json.at("max_penetration").number, 2.5e-7);
  // An empty summary is valid too (no warnings, no monitors).
  EXPECT_NO_THROW(static_cast<void>(parse_json(summary_json(RunSummary{}))));
}

TEST(Json, SummaryFileIsReplacedAtomically) {
  const TempDir dir("nmm_summary");
  RunSummary s;
  write_summary_json(dir.path() / "summary.json", s);
  s.status = "completed";
  write_summary_json(dir.path() / "summary.json", s);
  EXPECT_EQ(parse_json(read_text(dir.path() / "summary.json")).at("status").string, "completed");
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "summary.json.tmp"));
}

// ---------------------------------------------------------------------------------------
// Step data

TEST(StepOutput, PrincipalStressesAreOrderedAndTheDirectionIsAnEigenvector) {
  const std::vector<Eigen::Vector3d> states{{1.0e6, -2.0e6, 0.0},
                                            {-2.0e6, 1.0e6, 0.0},
                                            {0.0, 0.0, 3.0e6},
                                            {5.0, 5.0, 0.0},
                                            {-1.0e6, -3.0e6, 0.7e6}};
  for (const Eigen::Vector3d& s : states) {
    const PrincipalStress p = principal_stress(s);
    EXPECT_GE(p.s1, p.s2);
    EXPECT_NEAR(p.s1 + p.s2, s(0) + s(1), 1e-9 * (1.0 + s.norm()));
    EXPECT_NEAR(p.direction.norm(), 1.0, 1e-14);
    Eigen::Matrix2d tensor;
    tensor << s(0), s(2), s(2), s(1);
    EXPECT_NEAR((tensor * p.direction - p.s1 * p.direction).norm(), 0.0, 1e-9 * (1.0 + s.norm()));
  }
  const PrincipalStress shear = principal_stress({0.0, 0.0, 3.0e6});
  EXPECT_DOUBLE_EQ(shear.s1, 3.0e6);
  EXPECT_NEAR(shear.direction.x(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(shear.direction.y(), std::sqrt(0.5), 1e-15);
}

TEST(StepOutput, PrincipalAngleIsTheDirectionOfS1FromXInDegreesWithinMinus90To90) {
  const auto angle = [](double sxx, double syy, double sxy) {
    return principal_angle(principal_stress({sxx, syy, sxy}));
  };
  EXPECT_NEAR(angle(2.0, 1.0, 0.0), 0.0, 1e-12);
  EXPECT_NEAR(angle(0.0, 0.0, 3.0), 45.0, 1e-12);
  EXPECT_NEAR(angle(0.0, 0.0, -3.0), -45.0, 1e-12);
  EXPECT_NEAR(angle(-2.0, 1.0, 0.0), 90.0, 1e-12) << "s1 along y: +90, not -90";
  EXPECT_NEAR(angle(-2.0, 1.0, -1e-300), 90.0, 1e-12);
  // A direction pointing the other way along the same axis has the same angle.
  PrincipalStress flipped = principal_stress({1.0, 2.0, 1.0});
  const double along = principal_angle(flipped);
  flipped.direction = -flipped.direction;
  EXPECT_NEAR(principal_angle(flipped), along, 1e-12);
  EXPECT_NEAR(along,
              std::atan2(flipped.direction.y(), flipped.direction.x()) * 180.0 / std::numbers::pi +
                  180.0,
              1e-12);
}

TEST(StepOutput, ContactStatesAndStepPartsHaveNames) {
  EXPECT_STREQ(contact_state_name(ContactMode::open), "open");
  EXPECT_STREQ(contact_state_name(ContactMode::slide), "sliding");
  EXPECT_STREQ(contact_state_name(ContactMode::lock), "locked");
  EXPECT_EQ(step_part_names(), (std::vector<std::string>{"elements", "contacts", "boundaries"}));
}

TEST(StepOutput, CentroidSubtractsHolesWhateverTheLoopOrientation) {
  ModelElement element;
  // A 4 x 2 rectangle (clockwise) with a 1 x 1 hole (counter-clockwise) at its right end.
  element.polygons.push_back(
      {{{0, 0}, {0, 2}, {4, 2}, {4, 0}}, {{{3, 0.5}, {4 - 0.0, 0.5}, {4, 1.5}, {3, 1.5}}}});
  const Point2 c = element_centroid(element);
  // Rectangle area 8 at (2, 1), hole area 1 at (3.5, 1): (16 - 3.5) / 7.
  EXPECT_NEAR(c.x(), 12.5 / 7.0, 1e-14);
  EXPECT_NEAR(c.y(), 1.0, 1e-14);
}

TEST(StepOutput, StepFileNamesHaveSixDigitsAtLeast) {
  EXPECT_EQ(step_file_name(0), "step_000000.vtu");
  EXPECT_EQ(step_file_name(123), "step_000123.vtu");
  EXPECT_EQ(step_file_name(12345678), "step_12345678.vtu");
  EXPECT_EQ(contact_file_name(7), "contacts_000007.vtp");
  EXPECT_EQ(boundary_file_name(1234567), "boundary_1234567.vtp");
}

TEST(StepOutput, EveryArrayHasOneTuplePerPointOrCellAndTheStartHasNoDisplacement) {
  const TempDir dir("nmm_step_output");
  CaseAnalysis analysis(read_case_file(testing::write_case(dir.path(), testing::plate_case)));
  const Model& model = analysis.model();
  const std::vector<Point2> start = step_points(model);
  const PolygonMeshData data = make_step_data(model, start, analysis.stepper().velocity(), 0.25);
  ASSERT_EQ(data.points.size(), start.size());
  std::size_t n_cells = 0;
  for (const ModelElement& e : model.elements)
    n_cells += e.polygons.size();
  ASSERT_EQ(data.cells.size(), n_cells);
  struct Expected {
    const DataArrays* on;
    const char* name;
    int components;
    bool integer;
    std::vector<std::string> component_names;
  };
  const std::vector<std::string> xyz{"x", "y", "z"};
  const std::vector<Expected> expected{
      {&data.point_data, "displacement", 3, false, xyz},
      {&data.point_data, "velocity", 3, false, xyz},
      {&data.cell_data, "stress", 3, false, {"sxx", "syy", "sxy"}},
      {&data.cell_data, "principal_stresses", 2, false, {"s1", "s2"}},
      {&data.cell_data, "principal_direction", 3, false, xyz},
      {&data.cell_data, "principal_angle", 1, false, {}},
      {&data.cell_data, "element", 1, true, {}},
      {&data.cell_data, "material", 1, true, {}},
      {&data.cell_data, "block", 1, true, {}},
      {&data.cell_data, "kind", 1, true, {}}};
  for (const Expected& e : expected) {
    const DataArray* array = e.on->find(e.name);
    ASSERT_NE(array, nullptr) << e.name;
    EXPECT_EQ(array->n_components, e.components) << e.name;
    EXPECT_EQ(array->is_integer(), e.integer) << e.name;
    EXPECT_EQ(array->component_names, e.component_names) << e.name;
    EXPECT_EQ(array->n_tuples(), e.on == &data.point_data ? data.points.size() : n_cells) << e.name;
  }
  for (const double d : std::get<std::vector<double>>(data.point_data.find("displacement")->values))
    EXPECT_EQ(d, 0.0);
  for (const std::int32_t k :
       std::get<std::vector<std::int32_t>>(data.cell_data.find("kind")->values))
    EXPECT_EQ(k, static_cast<std::int32_t>(ElementKind::nmm));
  const DataArray* time = data.field_data.find("TimeValue");
  ASSERT_NE(time, nullptr);
  EXPECT_EQ(std::get<std::vector<double>>(time->values), std::vector<double>{0.25});
}

// ---------------------------------------------------------------------------------------
// Progress

TEST(Progress, TextShowsStepTimeStepContactsAndAnEstimate) {
  StepReport report;
  report.step = 50;
  report.time = 0.05;
  report.dt = 1e-3;
  report.open_close_iterations = 3;
  report.open_close_counted = 2;
  report.open_close_limit = 6;
  report.contacts = 12;
  RunProgress progress;
  progress.report = &report;
  progress.steps = 200;
  progress.end_time = std::numeric_limits<double>::infinity();
  EtaEstimate eta;
  eta.start(0.0, 0);
  eta.add(10.0, report.time, report.step);
  EXPECT_EQ(progress_text(progress, eta.seconds_left(progress.steps, progress.end_time)),
            "step 50/200  t = 0.05 s  dt = 0.001 s  open-close 2/6  contacts 12  ETA 30 s");
  // end_time ends the run first: the estimate follows simulated time.
  EXPECT_DOUBLE_EQ(eta.seconds_left(200, 0.1), 10.0);
  // Nothing to extrapolate from yet.
  EtaEstimate fresh;
  fresh.start(0.0, 0);
  EXPECT_NE(progress_text(progress, fresh.seconds_left(200, 0.1)).find("ETA ?"), std::string::npos);
}

TEST(Progress, LineSaysWhyStepsWereCut) {
  StepReport report;
  report.step = 7;
  report.open_close_counted = 6;
  report.open_close_limit = 60; // a settling static step: ten times open_close_max
  RunProgress progress;
  progress.report = &report;
  progress.steps = 10;
  progress.step_cuts = 4;
  progress.cuts.open_close = 2;
  progress.cuts.displacement = 1;
  progress.cuts.energy = 1;
  const std::string text = progress_text(progress, 5.0);
  EXPECT_NE(text.find("open-close 6/60"), std::string::npos) << text;
  EXPECT_NE(text.find("cuts 4 (open-close 2, displacement 1, energy 1)  ETA 5.00 s"),
            std::string::npos)
      << text;
  // After a restart the cuts before it have no known reason.
  progress.step_cuts = 6;
  progress.cuts = {};
  progress.cuts.not_finite = 1;
  EXPECT_NE(progress_text(progress, 5.0).find("cuts 6 (not finite 1, before the restart 5)"),
            std::string::npos)
      << progress_text(progress, 5.0);
  EXPECT_EQ(cut_reasons_text(CutCounts{}), "");
}

TEST(Progress, EstimateCountsEndTimeAndTheRecentCutSteps) {
  // 100 s of steps of 0.01 s at 0.1 s each (10 s of wall time per simulated second), then
  // 60 s of steps cut to a third, each with its cut tries: 0.2 s for 1/300 s (60 s per
  // simulated second). end_time 20 s ends the run long before its 10^6 steps.
  EtaEstimate eta;
  eta.start(0.0, 0);
  double wall = 0.0;
  double time = 0.0;
  long step = 0;
  for (int k = 0; k < 1000; ++k)
    eta.add(wall += 0.1, time += 0.01, ++step);
  EXPECT_NEAR(eta.seconds_left(1000000, 20.0), 10.0 * 10.0, 1e-6);
  for (int k = 0; k < 300; ++k)
    eta.add(wall += 0.2, time += 0.01 / 3.0, ++step);
  // The last 30 s are all cut steps: 60 s per simulated second for the 9 s still to go. A
  // step count (1300 steps in 160 s) would say about 1.2e5 s, the run's average rate 131 s.
  EXPECT_NEAR(eta.seconds_left(1000000, 20.0), 9.0 * 60.0, 0.5);
  // Without end_time the steps still to go, at the recent 0.2 s each.
  EXPECT_NEAR(eta.seconds_left(1400, std::numeric_limits<double>::infinity()), 100 * 0.2, 1e-3);
  // The run ends at whichever comes first: 100 steps more is less than 9 s of time.
  EXPECT_NEAR(eta.seconds_left(1400, 20.0), 100 * 0.2, 1e-3);
  // A restart starts from the checkpoint's time and step.
  EtaEstimate restarted;
  restarted.start(11.0, 1300);
  restarted.add(2.0, 11.0 + 0.1, 1330);
  EXPECT_NEAR(restarted.seconds_left(1000000, 20.0), 8.9 * 20.0, 1e-6);
}

TEST(Progress, StateLineComesOnItsOwnLineEveryThirtySeconds) {
  StepReport report;
  report.contacts = 114;
  report.sliding = 37;
  report.max_penetration = 3.14e-8;
  RunProgress progress;
  progress.report = &report;
  progress.steps = 100000;
  progress.end_time = std::numeric_limits<double>::infinity();
  const auto run = [&](ProgressMode mode) {
    std::ostringstream out;
    ProgressPrinter printer(out, mode);
    for (int k = 0; k < 1300; ++k) { // a step every 1/16 s: 81 s
      report.step = k + 1;
      report.time = 5e-4 * (k + 1);
      report.cuts_open_close = k == 700 ? 1 : 0;
      report.cuts_displacement = k == 800 ? 2 : 0;
      progress.wall_seconds = 0.0625 * (k + 1);
      printer.step(progress, false);
    }
    printer.finish();
    return out.str();
  };
  const std::string lines = run(ProgressMode::lines);
  EXPECT_EQ(lines.find('\r'), std::string::npos) << "no carriage return in a log";
  EXPECT_EQ(lines.find('\033'), std::string::npos) << "no terminal control in a log";
  const std::string first = "step 480 t = 0.24 s: 114 contacts closed, 37 sliding, deepest "
                            "penetration 3.1e-08 m; no cuts since step 0\n";
  const std::string second = "step 960 t = 0.48 s: 114 contacts closed, 37 sliding, deepest "
                             "penetration 3.1e-08 m; 3 cuts since step 480 (open-close 1, "
                             "displacement 2)\n";
  EXPECT_NE(lines.find("\n" + first), std::string::npos) << lines;
  EXPECT_NE(lines.find("\n" + second), std::string::npos) << lines;
  const std::string terminal = run(ProgressMode::terminal);
  // On a terminal the state line takes the progress line's place and ends it.
  EXPECT_NE(terminal.find('\r' + first.substr(0, first.size() - 1) + "\033[K\n"), std::string::npos)
      << terminal;
  EXPECT_NE(terminal.find(second.substr(0, second.size() - 1) + "\033[K\n"), std::string::npos);

  // The energy balance's part, when the run has one.
  progress.energy_balance = "energy balance: (its own words)";
  report.contacts = 0;
  EXPECT_EQ(state_text(progress, CutCounts{}, 1200),
            "step 1300 t = 0.65 s: no contact closed; no cuts since step 1200; energy balance: "
            "(its own words)");
}

TEST(Progress, PlainLinesComeAboutEveryTwoSecondsAndQuietPrintsNothing) {
  StepReport report;
  RunProgress progress;
  progress.report = &report;
  progress.steps = 10;
  std::ostringstream lines;
  ProgressPrinter printer(lines, ProgressMode::lines);
  for (int k = 0; k < 10; ++k) {
    report.step = k + 1;
    progress.wall_seconds = 0.5 * k; // 0 .. 4.5 s
    printer.step(progress, k == 9);
  }
  // At 0, 2 and 4 s, plus the forced last step.
  const std::string printed = lines.str();
  EXPECT_EQ(std::count(printed.begin(), printed.end(), '\n'), 4) << printed;

  std::ostringstream nothing;
  ProgressPrinter quiet(nothing, ProgressMode::quiet);
  quiet.phase("reading");
  quiet.warning("w");
  quiet.step(progress, true);
  quiet.finish();
  EXPECT_TRUE(nothing.str().empty());

  std::ostringstream terminal;
  ProgressPrinter line(terminal, ProgressMode::terminal);
  line.step(progress, true);
  line.finish();
  EXPECT_EQ(terminal.str().front(), '\r');
  EXPECT_EQ(terminal.str().back(), '\n');
}

TEST(Progress, ClosingSummarySaysStatusStepsWarningsAndWhereTheOutputsAre) {
  RunResult result;
  result.status = RunStatus::interrupted;
  result.steps = 120;
  result.time = 0.12;
  result.wall_seconds = 75.0;
  result.step_cuts = 1;
  result.max_penetration = 3.25e-6;
  result.output_dir = "results";
  result.output_steps = 13;
  result.warnings = {"case.toml:4: something"};
  std::ostringstream out;
  write_closing_summary(out, result, 2000);
  const std::string text = out.str();
  for (const char* part :
       {"interrupted", "120 of 2000 steps", "1 min 15 s", "1 step cut",
        "max contact penetration 3.25e-06 m", "warnings: 1", "case.toml:4: something",
        "results/case.pvd", "results/history.csv", "results/summary.json"})
    EXPECT_NE(text.find(part), std::string::npos) << part << " in\n" << text;
  EXPECT_EQ(text.find("friction:"), std::string::npos) << "no hold, no line";
  EXPECT_EQ(text.find("linear solves:"), std::string::npos) << "CHOLMOD alone, no line";
}

TEST(Progress, ClosingSummarySaysWhatTheChatterRuleHeldAtTheLimitOfFriction) {
  // Never silent (docs/formulation.md, "Chatter rule"): the friction of slides held at the
  // limit along motions that turned back in dynamic steps, with its share of the work of the
  // loads. Locks held beyond friction in static steps are a warning (io/case_runner.cpp), so
  // no info line for them.
  RunResult result;
  result.steps = 500;
  result.locks_beyond_friction = 8;
  result.max_lock_excess = 1.35;
  result.slides_against_motion = 91;
  result.slide_feed_work = 2.0e4;
  result.load_work = 5.16e5;
  std::ostringstream out;
  write_closing_summary(out, result, 500);
  const std::string text = out.str();
  const char* slide = "friction: 91 steps ended with a contact held sliding at its friction "
                      "limit against a motion that turned back (2e+04 J of friction work "
                      "along it, 3.9% of the work of the loads";
  EXPECT_NE(text.find(slide), std::string::npos) << text;
  EXPECT_EQ(text.find("held locked"), std::string::npos) << text;
}

TEST(Progress, ClosingSummarySaysWhatConjugateGradientsDidAndWhenCholmodIsFaster) {
  RunResult result;
  result.steps = 10;
  auto summary = [&](long solves, long iterations, long fallbacks) {
    result.solves = solves;
    result.cg_iterations = iterations;
    result.cg_fallbacks = fallbacks;
    std::ostringstream out;
    write_closing_summary(out, result, 10);
    return out.str();
  };
  const std::string all_by_cg = summary(14, 245, 0);
  EXPECT_NE(all_by_cg.find("linear solves: 14 (conjugate gradients: 245 iterations; 0 solves "
                           "left to CHOLMOD)\n"),
            std::string::npos)
      << all_by_cg;
  // A few solves left to CHOLMOD: no advice; more than half of them (a static analysis, as
  // examples/02: all 181): CHOLMOD alone is faster.
  const std::string few = summary(181, 4000, 20);
  EXPECT_EQ(few.find("is faster for this case"), std::string::npos) << few;
  const std::string most = summary(181, 4000, 100);
  EXPECT_NE(most.find("100 solves left to CHOLMOD); most systems were not for conjugate "
                      "gradients"),
            std::string::npos)
      << most;
  EXPECT_NE(most.find("solver = \"cholmod\" is faster for this case"), std::string::npos);
}

} // namespace
} // namespace nmm
