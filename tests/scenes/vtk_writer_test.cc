// ParaView output: one polyline per fibre and one vertex per contact point, with the arrays named.
#include "vtk_writer.h"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "iterative_solver.h"
#include "test_scenes.h"

namespace fibrecheck {
namespace {

TEST(VtkWriter, PolylinesForFibresVerticesForContacts) {
  Scene s = testing::crossing(0.5, 0.5, 1e-3);
  s.output.samples = 11;
  const Result r = solve_iteratively(s, SolverOptions::from_scene(s));
  const std::string path = ::testing::TempDir() + "crossing.vtp";
  write_vtk(path, s, r);
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  const std::string vtp = text.str();
  EXPECT_NE(vtp.find("<VTKFile type=\"PolyData\""), std::string::npos);
  EXPECT_NE(vtp.find("NumberOfPoints=\"23\""), std::string::npos);  // 2 × 11 samples + 1 contact
  EXPECT_NE(vtp.find("NumberOfVerts=\"1\""), std::string::npos);
  EXPECT_NE(vtp.find("NumberOfLines=\"2\""), std::string::npos);
  for (const char* array : {"Name=\"radius\"", "Name=\"displacement\"", "Name=\"force\""})
    EXPECT_NE(vtp.find(array), std::string::npos) << array;
  EXPECT_EQ(std::count(vtp.begin(), vtp.end(), '<'), std::count(vtp.begin(), vtp.end(), '>'));
  EXPECT_NE(vtp.find("</VTKFile>"), std::string::npos);
}

}  // namespace
}  // namespace fibrecheck
