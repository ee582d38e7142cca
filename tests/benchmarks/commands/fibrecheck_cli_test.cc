// The fibrecheck program as a user runs it: exit codes (0 converged, 2 bad input, 3 not solved),
// one clear message naming file, field and reason, and no file written for bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Outcome {
  int code;
  std::string out, err;
};

std::string slurp(const std::string& path) {
  std::stringstream s;
  s << std::ifstream(path).rdbuf();
  return s.str();
}

/// Runs the program; its output goes to files named after the running test, since ctest runs
/// tests in parallel.
Outcome run(const std::string& arguments) {
  const std::string base = ::testing::TempDir() + "cli_" +
                           ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const std::string command =
      std::string(FIBRECHECK_BINARY) + " " + arguments + " >" + base + ".out 2>" + base + ".err";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(base + ".out"), slurp(base + ".err")};
}

std::string scene(const std::string& name) {
  return std::string(FIBRECHECK_SCENES_DIR) + "/" + name + ".json";
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ::testing::TempDir() + "cli_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name() + "/";
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string write(const std::string& name, const json& doc) {
    std::ofstream(dir_ + name) << doc.dump();
    return dir_ + name;
  }
  std::string write_text(const std::string& name, const std::string& text) {
    std::ofstream(dir_ + name) << text;
    return dir_ + name;
  }
  json crossing() { return json::parse(slurp(scene("two_fibres_crossing"))); }
  std::string dir_;
};

TEST_F(Cli, SolveWritesResultAndVtkAndExitsZero) {
  const Outcome r = run("solve " + scene("two_fibres_crossing") + " --out " + dir_ +
                        "r.json --vtk " + dir_ + "r.vtp");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("status converged"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rule accelerated"), std::string::npos);  // the default
  EXPECT_NE(r.out.find("2/lambda_max(W)"), std::string::npos);
  EXPECT_EQ(json::parse(slurp(dir_ + "r.json"))["status"], "converged");
  EXPECT_TRUE(fs::exists(dir_ + "r.vtp"));
}

// The parallel fibres at t_d = 1e-8 mm: rule seed with c = 0.02 N/mm (c/n = 1e-3 N/mm per slice)
// is below its stable limit 2/λmax(D½WD½) ≈ 0.032 N/mm, and converges.
TEST_F(Cli, CommandLineOverridesRuleSlicesAndC) {
  json parallel = json::parse(slurp(scene("parallel_fibres")));
  parallel["solver"]["overlap_tolerance"] = 1e-8;
  const Outcome r = run("solve " + write("parallel.json", parallel) +
                        " --rule seed --c 0.02 --slices 20 --out " + dir_ + "r.json -q");
  const json result = json::parse(slurp(dir_ + "r.json"));
  EXPECT_EQ(result["rule"], "seed");
  EXPECT_EQ(result["c"], 0.02);
  EXPECT_EQ(result["contacts"][0]["points"].size(), 20u);
  EXPECT_GT(result["c_stable_limit"].get<double>(), 0.02);
  EXPECT_EQ(result["status"], "converged");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "");  // quiet
  // The scene's own rule (accelerated) and slices (100) when nothing overrides them.
  run("solve " + write("plain.json", parallel) + " --out " + dir_ + "plain.json -q");
  const json plain = json::parse(slurp(dir_ + "plain.json"));
  EXPECT_EQ(plain["rule"], "accelerated");
  EXPECT_EQ(plain["contacts"][0]["points"].size(), 100u);
}

// The slicing estimate of the parallel fibres (100 slices against 50): the line force's first-order
// slicing error, 2.4e-3 below the closed form q·EI_B/(EI_A + EI_B) (the slicing estimate's own test
// checks it against the closed form; here, that the program writes and prints it). A coarse count
// not below the scene's is bad input.
TEST_F(Cli, SolveEstimatesTheSlicingErrorOnRequest) {
  const Outcome r =
      run("solve " + scene("parallel_fibres") + " --estimate-slicing --out " + dir_ + "r.json");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("estimated slicing error (100 against 50 slices)"), std::string::npos)
      << r.out;
  const json e = json::parse(slurp(dir_ + "r.json"))["slicing_error_estimate"];
  EXPECT_EQ(e["coarse_slices"], 50);
  EXPECT_EQ(e["orders"]["force"], 1.0);
  EXPECT_EQ(e["coarser_slices"], 25);
  EXPECT_NEAR(e["observed_orders"]["force"].get<double>(), 1.0, 0.1);
  EXPECT_EQ(r.out.find("slicing estimate uncertain"), std::string::npos) << r.out;
  EXPECT_GT(e["force"].get<double>(), 1.2e-3);
  EXPECT_LT(e["force"].get<double>(), 4.8e-3);
  run("solve " + scene("parallel_fibres") + " --out " + dir_ + "plain.json -q");
  EXPECT_FALSE(json::parse(slurp(dir_ + "plain.json")).contains("slicing_error_estimate"));
  const Outcome bad = run("solve " + scene("parallel_fibres") +
                          " --estimate-slicing --coarse-slices 100 --out " + dir_ + "bad.json");
  EXPECT_EQ(bad.code, 2) << bad.err;
  EXPECT_NE(bad.err.find("--coarse-slices"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ + "bad.json"));
}

TEST_F(Cli, BadInputExitsTwoWithFileFieldReasonAndWritesNothing) {
  json negative = crossing();
  negative["fibres"][1]["radius"] = -0.01;
  json unknown = crossing();
  unknown["solver"]["overlap_tolerence"] = 1e-9;
  json missing = crossing();
  missing["loads"] = json::parse(R"([{"fibre": "Z", "force": [0,0,1]}])");
  json zero_slices = crossing();
  zero_slices["contact"]["slices"] = 0;
  std::ofstream(dir_ + "truncated.json") << crossing().dump().substr(0, 50);
  const std::pair<std::string, std::string> cases[] = {
      {write("negative.json", negative), "fibres[1].radius"},
      {write("unknown.json", unknown), "solver.overlap_tolerence"},
      {write("missing.json", missing), "loads[0].fibre"},
      {write("zero_slices.json", zero_slices), "contact.slices"},
      {dir_ + "truncated.json", "malformed JSON"},
      {dir_ + "absent.json", "no such file"},
  };
  for (const auto& [path, field] : cases) {
    const Outcome r =
        run("solve " + path + " --out " + dir_ + "out.json --vtk " + dir_ + "out.vtp");
    EXPECT_EQ(r.code, 2) << path << ": " << r.err;
    EXPECT_NE(r.err.find(path), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(field), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;  // one message
    EXPECT_FALSE(fs::exists(dir_ + "out.json")) << path;
    EXPECT_FALSE(fs::exists(dir_ + "out.vtp")) << path;
  }
  // A bad scene among good ones: nothing is solved or written.
  const Outcome mixed = run("solve " + scene("two_fibres_crossing") + " " +
                            write("neg.json", negative) + " --out-dir " + dir_ + "all");
  EXPECT_EQ(mixed.code, 2);
  EXPECT_FALSE(fs::exists(dir_ + "all"));
  EXPECT_EQ(run("solve " + scene("two_fibres_crossing") + " --rule fastest").code, 2);
  EXPECT_EQ(run("solve " + scene("two_fibres_crossing") + " --slices 0").code, 2);
  EXPECT_EQ(run("frobnicate").code, 2);
}

TEST_F(Cli, UnsolvableSceneWritesItsStatusAndExitsThree) {
  json pinned = crossing();
  pinned["fibres"][1]["start"] = {0, 0, 0.015};
  pinned["fibres"][1]["end"] = {0, 1, 0.015};
  const Outcome r = run("solve " + write("pinned.json", pinned) + " --out " + dir_ + "r.json");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("unresolvable"), std::string::npos);
  EXPECT_NE(r.err.find("A and B"), std::string::npos) << r.err;
  EXPECT_EQ(json::parse(slurp(dir_ + "r.json"))["status"], "unresolvable");
  json capped = json::parse(slurp(scene("parallel_fibres")));
  capped["solver"]["max_iterations"] = 3;
  const Outcome c = run("solve " + write("capped.json", capped) + " --out " + dir_ + "c.json");
  EXPECT_EQ(c.code, 3);
  EXPECT_EQ(json::parse(slurp(dir_ + "c.json"))["status"], "max_iterations");
}

TEST_F(Cli, HelpScenePrintsTheFormat) {
  const Outcome r = run("solve --help-scene");
  EXPECT_EQ(r.code, 0);
  for (const char* field : {"youngs_modulus", "force_per_length", "overlap_tolerance", "slices"})
    EXPECT_NE(r.out.find(field), std::string::npos) << field;
}

TEST_F(Cli, GenerateTowIsDeterministicAndChecksItsOptions) {
  EXPECT_EQ(run("generate tow --fibres 30 --slices 20 --seed 3 --out " + dir_ + "a.json").code, 0);
  EXPECT_EQ(run("generate tow --fibres 30 --slices 20 --seed 3 --out " + dir_ + "b.json").code, 0);
  EXPECT_EQ(slurp(dir_ + "a.json"), slurp(dir_ + "b.json"));
  const json tow = json::parse(slurp(dir_ + "a.json"));
  EXPECT_EQ(tow["fibres"].size(), 30u);
  EXPECT_EQ(tow["contact"]["slices"], 20);
  const Outcome bad = run("generate tow --fibres 30 --compaction 1.5 --out " + dir_ + "c.json");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--compaction"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir_ + "c.json"));
  // The generated scene solves.
  EXPECT_EQ(
      run("solve " + dir_ + "a.json --rule accelerated -q --out " + dir_ + "a.result.json").code,
      0);
}

#ifdef FIBRECHECK_WITH_FEM
TEST_F(Cli, MeshWritesGmshFilesAndRejectsBadScenes) {
  const Outcome ok = run("mesh " + scene("two_fibres_crossing") + " --out " + dir_ +
                         "meshes/m.msh --geo " + dir_ + "m.geo");
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_NE(slurp(dir_ + "meshes/m.msh").find("$PhysicalNames"), std::string::npos);
  EXPECT_NE(slurp(dir_ + "m.geo").find("Physical Curve(\"A\""), std::string::npos);
  json negative = crossing();
  negative["fibres"][0]["youngs_modulus"] = 0;
  const Outcome bad = run("mesh " + write("bad.json", negative) + " --out " + dir_ + "bad.msh");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("fibres[0].youngs_modulus"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ + "bad.msh"));
}

TEST_F(Cli, FemWritesTheSameResultSchema) {
  const Outcome ok = run("fem " + scene("two_fibres_crossing") + " --out " + dir_ + "f.json");
  EXPECT_EQ(ok.code, 0) << ok.err;
  const json fem = json::parse(slurp(dir_ + "f.json"));
  run("solve " + scene("two_fibres_crossing") + " -q --out " + dir_ + "i.json");
  const json iterative = json::parse(slurp(dir_ + "i.json"));
  EXPECT_EQ(fem["solver"], "fem");
  EXPECT_EQ(fem["status"], "converged");
  // Every field but the iterative solver's estimate of its own iteration error (the reference
  // has none to estimate).
  for (auto it = iterative.begin(); it != iterative.end(); ++it)
    if (it.key() != "error_estimate") {
      EXPECT_TRUE(fem.contains(it.key())) << it.key();
    }
  EXPECT_TRUE(iterative.contains("error_estimate"));
  EXPECT_NEAR(fem["contacts"][0]["total_force"].get<double>(),
              iterative["contacts"][0]["total_force"].get<double>(), 1e-8 * 1.5e-5);
  json negative = crossing();
  negative["fibres"][1]["radius"] = -1;
  const Outcome bad = run("fem " + write("bad.json", negative) + " --out " + dir_ + "bad.json.out");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("fibres[1].radius"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ + "bad.json.out"));
}

// The final step's contact problem for outside solvers: the scene's one contact, its compliance
// and overlap, the reference's answer; a frictional scene's problem has the tangents.
TEST_F(Cli, FemExportsTheContactProblem) {
  const Outcome ok = run("fem -q " + scene("two_fibres_crossing") + " --out " + dir_ +
                         "f.json --export-contact-problem " + dir_ + "p.json");
  EXPECT_EQ(ok.code, 0) << ok.err;
  const json problem = json::parse(slurp(dir_ + "p.json"));
  const json fem = json::parse(slurp(dir_ + "f.json"));
  EXPECT_EQ(problem["format"], "fibrecheck-contact-problem");
  ASSERT_EQ(problem["contacts"].size(), 1u);
  EXPECT_EQ(problem["contacts"][0]["tangents"], 0);
  EXPECT_NEAR(problem["q"][0].get<double>(), 1e-3, 1e-12);  // the scene's overlap
  // P = δ/W, the force in the result.
  const double P = problem["reference"]["reaction"][0].get<double>();
  EXPECT_NEAR(P * problem["W"]["values"][0].get<double>(), 1e-3, 1e-12);
  EXPECT_NEAR(P, fem["contacts"][0]["total_force"].get<double>(), 1e-12 * P);
  json frictional = crossing();
  frictional["contact"]["friction"] = 0.3;
  const Outcome with_friction = run("fem -q " + write("friction.json", frictional) +
                                    " --export-contact-problem " + dir_ + "pf.json");
  EXPECT_EQ(with_friction.code, 0) << with_friction.err;
  const json pf = json::parse(slurp(dir_ + "pf.json"));
  EXPECT_EQ(pf["contacts"][0]["tangents"], 2);
  EXPECT_EQ(pf["q"].size(), 3u);
  EXPECT_EQ(pf["mu"], 0.3);
}

#ifdef FIBRECHECK_HAVE_SICONOS
// The scale study on two small tows: every run its own process, the reference and Siconos at the
// smaller; a second run computes nothing again; the report gains its Scale table and figure.
TEST_F(Cli, ScaleStudyMeasuresEveryRunAndResumes) {
  const std::string out = dir_ + "scale";
  const std::string args =
      "study scale --fibres 7,19 --slices 10 --reference-fibres 7 "
      "--peer-fibres 7 --peer-solvers lemke,pgs,newton --processes 1 -q "
      "--out " +
      out;
  const Outcome ok = run(args);
  ASSERT_EQ(ok.code, 0) << ok.err;
  const json study = json::parse(slurp(out + "/scale_study.json"));
  // The program that only starts maps the same libraries as every run: a floor under each of
  // them (5 MB for the pages a run's own code touches besides).
  const double floor = study["program_floor_memory_mb"].get<double>();
  EXPECT_GT(floor, 1.0);
  int iterative = 0, fem = 0, siconos = 0;
  for (const json& p : study["points"]) {
    SCOPED_TRACE(p.dump());
    // Lemke's pivoting need not find the answer on every CPU (siconos_cross_check_test.cc): a
    // failed Lemke run must be shown as failed; every other run converges.
    if (p["solver"] == "siconos" && p["method"] == "lemke" && p["status"] != "converged") {
      EXPECT_TRUE(p["status"] == "diverged" || p["status"] == "max_iterations");
      ++siconos;
      continue;
    }
    EXPECT_EQ(p["status"], "converged");
    EXPECT_GT(p["candidates"].get<long>(), 0);
    EXPECT_GT(p["active"].get<long>(), 0);
    EXPECT_LE(p["active"].get<long>(), p["candidates"].get<long>());
    EXPECT_GT(p["peak_memory_mb"].get<double>(), 1.0);
    EXPECT_GT(p["peak_proportional_memory_mb"].get<double>(), 0.0);
    EXPECT_LE(p["peak_proportional_memory_mb"].get<double>(),
              p["peak_memory_mb"].get<double>() + 1.0);
    if (p["solver"] != "siconos") {
      EXPECT_LE(floor, p["peak_memory_mb"].get<double>() + 5.0);
    }
    if (p["solver"] == "iterative") {
      ++iterative;
      EXPECT_GT(p["iterations"].get<long>(), 0);
    }
    if (p["solver"] == "fem") {
      ++fem;
      EXPECT_GT(p["unknowns"].get<long>(), 0);
    }
    if (p["solver"] == "siconos") {
      ++siconos;
      // The same problem as the reference's, solved again: the same answer.
      EXPECT_GE(p["agreement"].get<double>(), 0.0);
      EXPECT_LE(p["agreement"].get<double>(), 1e-8);
    }
  }
  EXPECT_EQ(iterative, 4);  // auto and accelerated at 7 and 19 fibres
  EXPECT_EQ(fem, 1);
  EXPECT_EQ(siconos, 3);  // lemke, pgs, newton
  EXPECT_EQ(study["exponents"].size(), 2u);
  // The same pushing contacts in every run of the 7-fibre tow.
  long active = -1;
  for (const json& p : study["points"])
    if (p["fibres"] == 7 && p["status"] == "converged") {
      if (active < 0) active = p["active"].get<long>();
      EXPECT_EQ(p["active"].get<long>(), active) << p.dump();
    }
  const std::string points = slurp(out + "/scale_study.points.jsonl");
  ASSERT_EQ(run(args).code, 0);
  EXPECT_EQ(slurp(out + "/scale_study.points.jsonl"), points);
  ASSERT_EQ(run("report " + out + " --out " + dir_ + "report").code, 0);
  const std::string report = slurp(dir_ + "report/report.md");
  EXPECT_NE(report.find("## Scale"), std::string::npos);
  EXPECT_NE(report.find("Siconos lemke"), std::string::npos);
  // A peer size the reference does not run: bad input, nothing written.
  const Outcome bad =
      run("study scale --fibres 7 --reference-fibres 7 --peer-fibres 19 -q --out " + dir_ + "bad");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--peer-fibres"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ + "bad"));
}
#endif

// The friction study's options are checked before it writes anything: a volume fraction no tow
// can be packed at names its field and leaves no folder.
TEST_F(Cli, FrictionStudyRefusesATowItCannotMakeAndWritesNothing) {
  const Outcome bad =
      run("study friction --fibres 7 --volume-fraction 0.85 -q --out " + dir_ + "bad");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("volume_fraction"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ + "bad"));
  EXPECT_EQ(run("study friction --fibres 0 --out " + dir_ + "none").code, 2);
  EXPECT_FALSE(fs::exists(dir_ + "none"));
}

// Each kind of bad input: one message naming what is wrong, exit code 2, nothing written.
// Damaged scene files through the program itself (the scene reader sees thousands in-process,
// see scene_mutation_test.cc): every one ends with exit code 0, 2 or 3 and a message, and bad
// input writes nothing.
TEST_F(Cli, DamagedScenesExitWithZeroTwoOrThree) {
  const std::string text = slurp(scene("small_tow_19"));
  for (int i = 0; i < 24; ++i) {
    std::string damaged = text;
    if (i % 2 == 0) {
      damaged = text.substr(0, (text.size() * (i + 1)) / 25);  // truncated
    } else {
      damaged[(text.size() * static_cast<std::size_t>(i)) / 25] ^= 0x5a;  // a byte flipped
    }
    const std::string file = write_text("damaged" + std::to_string(i) + ".json", damaged);
    const std::string out = dir_ + "damaged" + std::to_string(i) + ".result.json";
    const Outcome r = run("solve -q " + file + " --out " + out);
    EXPECT_TRUE(r.code == 0 || r.code == 2 || r.code == 3) << r.code << "\n" << r.err;
    if (r.code == 2) {
      EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
      EXPECT_FALSE(fs::exists(out));
    } else {
      EXPECT_TRUE(fs::exists(out)) << r.err;
    }
    if (r.code == 3) {
      EXPECT_FALSE(r.err.empty());
    }
  }
}

TEST_F(Cli, FemRejectsBadInputWithoutWritingAnything) {
  const std::string out = " --out " + dir_ + "never.json";
  struct Case {
    std::string arguments, says;
  };
  for (const Case& k :
       {Case{"fem " + dir_ + "missing.json" + out, "no such file"},
        Case{"fem " + write_text("broken.json", "{\"fibres\": [") + out, "broken.json"},
        Case{"fem " + scene("two_fibres_crossing") + " --line-contact sideways" + out,
             "--line-contact"},
        Case{"fem " + scene("two_fibres_crossing") + " --refine -1" + out, "--refine"},
        Case{"fem " + scene("two_fibres_crossing") + " --line-contact continuous --refine -3" + out,
             "--refine"},
        Case{"fem " + scene("two_fibres_crossing") +
                 " --line-contact continuous --refine -2 --slices 6" + out,
             "coarsest continuous line contact for 6 slices is K = 0"},
        Case{"fem " + scene("two_fibres_crossing") + " --vtk " + dir_ + "b.vtk" + out, "--vtk"},
        Case{"fem " + scene("two_fibres_crossing") + " --refine auto" + out,
             "--line-contact continuous"}}) {
    const Outcome bad = run(k.arguments);
    EXPECT_EQ(bad.code, 2) << k.arguments;
    EXPECT_NE(bad.err.find(k.says), std::string::npos) << k.arguments << "\n" << bad.err;
    EXPECT_FALSE(fs::exists(dir_ + "never.json")) << k.arguments;
  }
}

// The compaction study refuses what it cannot measure before it writes anything: a scene without
// walls (no pressure), one without a load path unless --steps gives one, a compaction beyond (0,
// 1].
TEST_F(Cli, CompactionStudyRefusesScenesItCannotCompact) {
  const std::string out = " --out " + dir_ + "study";
  struct Case {
    std::string arguments, says;
  };
  for (const Case& k :
       {Case{"study compaction " + scene("two_fibres_crossing") + " --steps 3" + out, "walls"},
        Case{"study compaction " + scene("compaction_test") + out, "steps"},
        Case{"study compaction " + scene("compaction_test") + " --steps 3 --final-compaction 2" +
                 out,
             "--final-compaction"}}) {
    const Outcome bad = run(k.arguments);
    EXPECT_EQ(bad.code, 2) << k.arguments;
    EXPECT_NE(bad.err.find(k.says), std::string::npos) << k.arguments << "\n" << bad.err;
    EXPECT_FALSE(fs::exists(dir_ + "study")) << k.arguments;
  }
}

// A study's long iterative runs say where they stand, every --progress seconds: here at every
// check, so that each step of the load path is seen; none with -q, none in a run shorter than the
// default minute. The summary names each run's geometry.
TEST_F(Cli, CompactionStudyRunsSayWhereTheyStand) {
  const std::string study = "study compaction " + scene("compaction_test") +
                            " --steps 3 --reference-fibres 1 --out " + dir_;
  const Outcome often = run(study + "often --progress 1e-9");
  ASSERT_EQ(often.code, 0) << often.err;
  for (const char* step :
       {"step 1 of 3, iteration 1/", "step 2 of 3, iteration 1/", "step 3 of 3, iteration 1/"})
    EXPECT_NE(often.err.find(step), std::string::npos) << step << "\n" << often.err;
  EXPECT_NE(often.out.find("deformed"), std::string::npos) << often.out;
  EXPECT_NE(often.out.find("linearised"), std::string::npos) << often.out;
  const Outcome quiet = run(study + "quiet --progress 1e-9 -q");
  EXPECT_EQ(quiet.code, 0);
  EXPECT_EQ(quiet.err, "");
  const Outcome plain = run(study + "plain");
  EXPECT_EQ(plain.code, 0);
  EXPECT_EQ(plain.err.find("iteration"), std::string::npos) << plain.err;
  EXPECT_NE(plain.err.find("compaction study: point 1 of 2"), std::string::npos) << plain.err;
  EXPECT_EQ(run(study + "never --progress -1").code, 2);
}

// Continuous line contact with a refinement, and the beams for ParaView through DataOut.
TEST_F(Cli, FemContinuousLineContactAndParaViewBeams) {
  const Outcome ok = run("fem " + scene("parallel_fibres") +
                         " -q --slices 20 --line-contact continuous --refine 1 --out " + dir_ +
                         "c.json --vtk " + dir_ + "beams/c.vtu");
  EXPECT_EQ(ok.code, 0) << ok.err;
  const json r = json::parse(slurp(dir_ + "c.json"));
  const auto& stages = r["stages"];
  EXPECT_NE(std::find(stages.begin(), stages.end(), "continuous_line_contact"), stages.end());
  // 20 cells refined once, two Gauss points each.
  EXPECT_EQ(r["contacts"][0]["points"].size(), 80u);
  EXPECT_NE(slurp(dir_ + "beams/c.vtu").find("\"displacement\""), std::string::npos);
}

// compare on the crossing: point contacts only, so the reference on slices is the ground truth,
// the slicing error is zero and the user's run agrees with it to the iteration's tolerance
// (t_d = 1e-9 mm on deflections of ~1e-3 mm).
TEST_F(Cli, CompareTwoCrossingFibresAgreesAndWritesEveryResult) {
  const Outcome r = run("compare " + scene("two_fibres_crossing") + " --out " + dir_ + "cmp -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const json c = json::parse(slurp(dir_ + "cmp/two_fibres_crossing/compare.json"));
  EXPECT_TRUE(c["comparable"].get<bool>());
  EXPECT_EQ(c["ground_truth"], "reference_slices");
  for (const char* metric : {"deflection_error", "force_error", "energy_error"}) {
    EXPECT_LT(c[metric].get<double>(), 1e-6) << metric;
    EXPECT_EQ(c["slicing_error"][metric].get<double>(), 0.0) << metric;
    EXPECT_DOUBLE_EQ(c["iteration_error"][metric].get<double>(), c[metric].get<double>());
  }
  ASSERT_EQ(c["pairs"].size(), 1u);
  for (const auto& [label, file] : c["files"].items())
    EXPECT_TRUE(fs::exists(dir_ + "cmp/two_fibres_crossing/" + file.get<std::string>())) << label;
  // The same errors from the stored results, without running a solver.
  const Outcome stored = run(
      "compare --run " + dir_ + "cmp/two_fibres_crossing/user.result.json" + " --truth " + dir_ +
      "cmp/two_fibres_crossing/reference_slices.result.json" + " --out " + dir_ + "stored.json -q");
  ASSERT_EQ(stored.code, 0) << stored.err;
  EXPECT_DOUBLE_EQ(json::parse(slurp(dir_ + "stored.json"))["force_error"].get<double>(),
                   c["force_error"].get<double>());
  // A bad scene among good ones: exit 2, nothing written.
  json negative = crossing();
  negative["fibres"][1]["radius"] = -0.01;
  const Outcome bad = run("compare " + scene("two_fibres_crossing") + " " +
                          write("neg.json", negative) + " --out " + dir_ + "bad -q");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("fibres[1].radius"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ + "bad"));
}
#endif

}  // namespace
