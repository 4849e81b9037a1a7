//! The library's logger (log.h): what OpenMesh writes to its error stream reaches the logger at
//! debug level instead of stderr.
#include "sdflow/log.h"
#include "sdflow/mesh.h"

#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>

#include <sstream>

namespace sdflow {
namespace {

TEST(Log, openmesh_complaints_go_to_the_logger_not_to_stderr)
{
  std::ostringstream log;
  auto sink = std::make_shared<spdlog::sinks::ostream_sink_st>(log);
  auto capture = std::make_shared<spdlog::logger>("sdflow", sink);
  capture->set_level(spdlog::level::debug);
  set_logger(capture);
  // A third triangle on one edge: OpenMesh refuses it ("complex edge") and says so.
  Mesh mesh;
  std::vector<Mesh::VertexHandle> v;
  for (const auto& p : {Mesh::Point(0, 0, 0), Mesh::Point(1, 0, 0), Mesh::Point(0, 1, 0), Mesh::Point(0, -1, 0),
                        Mesh::Point(0, 0, 1)})
    v.push_back(mesh.add_vertex(p));
  ASSERT_TRUE(mesh.add_face(v[0], v[1], v[2]).is_valid());
  ASSERT_TRUE(mesh.add_face(v[1], v[0], v[3]).is_valid());
  testing::internal::CaptureStderr();
  const auto refused = mesh.add_face(v[0], v[1], v[4]);
  const std::string printed = testing::internal::GetCapturedStderr();
  set_logger(std::make_shared<spdlog::logger>("sdflow"));
  EXPECT_FALSE(refused.is_valid());
  EXPECT_EQ(printed, "");
  EXPECT_NE(log.str().find("OpenMesh: PolyMeshT::add_face"), std::string::npos) << log.str();
}

} // namespace
} // namespace sdflow
