//! libFuzzer harness: the repair (io/repair.h) on soups no reader would produce (fuzz_soup.h);
//! flag bit 3 merges vertices within (flags >> 4) / 150 of the bounding-box diagonal. Besides a
//! crash, a repaired mesh that a second repair would change is a finding: the result must be valid
//! and oriented as reading it builds it, so repairing it again must make no repair and keep every
//! position and face.
#include "fuzz_common.h"
#include "fuzz_soup.h"

#include "sdflow/io/repair.h"

#include <cstdio>
#include <cstdlib>

namespace {

//! The soup of a mesh's positions and triangles, as a file written from it would read.
sdflow::PolygonSoup soup_of(const sdflow::Mesh& mesh)
{
  const sdflow::VertexVectors positions = sdflow::vertex_positions(mesh);
  const sdflow::FaceIndices faces = sdflow::face_indices(mesh);
  sdflow::PolygonSoup soup;
  for (Eigen::Index i = 0; i < positions.rows(); ++i)
    soup.points.push_back(positions.row(i).transpose());
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    soup.polygons.push_back({faces(f, 0), faces(f, 1), faces(f, 2)});
  return soup;
}

[[noreturn]] void finding(const char* what)
{
  std::fprintf(stderr, "fuzz_repair: %s\n", what);
  std::abort();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  sdflow::fuzz::quiet();
  const auto [soup, flags] = sdflow::fuzz::decode_soup(data, size);
  sdflow::RepairOptions options;
  if (flags & 8)
    options.merge_tolerance = (flags >> 4) / 150.0;
  sdflow::RepairResult repaired;
  try {
    repaired = sdflow::repair_soup(soup, "fuzz", options);
  } catch (const sdflow::Error&) {
    return 0;
  }
  if (repaired.face_origin.size() != repaired.mesh.n_faces())
    finding("face_origin does not have one entry per face");
  const sdflow::PolygonSoup result = soup_of(repaired.mesh);
  sdflow::RepairResult again;
  try {
    again = sdflow::repair_soup(result, "fuzz");
  } catch (const sdflow::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    finding("the repaired mesh is refused by a second repair");
  }
  if (!again.repairs.empty()) {
    for (const sdflow::Repair& r : again.repairs)
      std::fprintf(stderr, "%s\n", r.message.c_str());
    finding("a second repair repairs the repaired mesh");
  }
  if (sdflow::vertex_positions(again.mesh) != sdflow::vertex_positions(repaired.mesh) ||
      sdflow::face_indices(again.mesh) != sdflow::face_indices(repaired.mesh))
    finding("a second repair changes the repaired mesh");
  return 0;
}
