// Hostile input: each test here failed on the loaders before the fixes -
// a crash or garbage triangle, an endless read, a hang on a FIFO, a silently truncated
// number or path, a quoted secret - and now gets an error naming the input and the cause.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "common/util/source_tree.h"
#include "sw/isect/geometry/io.h"
#include "sw/scene/isolate.h"
#include "sw/scene/mesh.h"
#include "sw/scene/scene.h"

namespace rt {
namespace {

std::string dir() {
  static const std::string d = [] {
    std::string t = ::testing::TempDir();
    while (t.size() > 1 && t.back() == '/') t.pop_back();
    std::string p = t + "/hostile-XXXXXX";
    if (!::mkdtemp(&p[0])) std::abort();
    return p;
  }();
  return d;
}

std::string write(const std::string& name, const std::string& bytes) {
  const std::string p = dir() + "/" + name;
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

std::string scene_for(const std::string& mesh_file) {
  return R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1], "up": [0,1,0], "fov_y_deg": 50},
    "lights": [{"position": [0, 2, 0]}], "materials": {"m": {}}, "meshes": [{"file": ")" +
         mesh_file + R"(", "material": "m"}]})";
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

std::string scene_error(const std::string& json_name) {
  return error_of([&] { load_scene(dir() + "/" + json_name); });
}

TEST(HostileInput, BareCarriageReturnEndsACommentLikeANewline) {
  // A comment ending in a bare \r: the next statement is a statement (its bad index an
  // error), never hidden from one reader and parsed by another.
  write("cr.obj", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\n# c\rf 1 2 9\n");
  write("cr.json", scene_for("cr.obj"));
  EXPECT_EQ(scene_error("cr.json"),
            dir() + "/cr.obj:5: face refers to vertex 9 of 3");
  write("crok.obj", "v 0 0 -3\rv 1 0 -3\r\nv 0 1 -3\n# c\rf 1 2 3\r");
  write("crok.json", scene_for("crok.obj"));
  EXPECT_EQ(load_scene(dir() + "/crok.json").triangles.size(), 1u);
}

TEST(HostileInput, ObjCommentsByteOrderMarksAndRepeatedCorners) {
  write("c.obj", "\xEF\xBB\xBFv 0 0 -3 # a\nv 1 0 -3\nv 0 1 -3\nf 1 2 3 # trailing comment\nf 1 2 3 1 2 3\n");
  write("c.json", scene_for("c.obj"));
  const Scene s = load_scene(dir() + "/c.json");
  // The second face goes round the triangle twice: it is kept (4 triangles, two of them
  // without area), not dropped.
  ASSERT_EQ(s.triangles.size(), 5u);
  int with_area = 0;
  for (const auto& t : s.triangles) with_area += glm::length(glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0])) > 0;
  EXPECT_EQ(with_area, 3);
}

TEST(HostileInput, MaterialLibrariesAreReadOnlyBesideTheMesh) {
  // A FIFO as material library would block any reader that opens it; /dev/zero never
  // ends. Libraries are read only as regular .mtl files in the mesh's own
  // directory, within the limits; anything else is an error naming the OBJ line.
  const std::string fifo = dir() + "/block.mtl";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  write("mtl.obj", "mtllib block.mtl\nv 0 0 -3\nv 1 0 -3\nv 0 1 -3\nusemtl x\nf 1 2 3\n");
  write("mtl.json", scene_for("mtl.obj"));
  EXPECT_EQ(scene_error("mtl.json"),
            dir() + "/mtl.obj:1: mtllib 'block.mtl': " + fifo + ": cannot read material library: not a regular file (FIFO)");
  write("zero.obj", "mtllib ../../../../../../dev/zero\nv 0 0 -3\nv 1 0 -3\nv 0 1 -3\nusemtl x\nf 1 2 3\n");
  write("zero.json", scene_for("zero.obj"));
  EXPECT_EQ(scene_error("zero.json"), dir() + "/zero.obj:1: mtllib '../../../../../../dev/zero': not beside the mesh (a "
                                              "material library must be in the mesh's own directory)");
}

TEST(HostileInput, SpecialFilesAreRefusedBeforeReading) {
  const std::string fifo = dir() + "/in.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(error_of([] { load_scene("/dev/zero"); }), "/dev/zero: cannot read scene: not a regular file (character device)");
  EXPECT_EQ(error_of([&] { load_scene(fifo); }), fifo + ": cannot read scene: not a regular file (FIFO)");
  EXPECT_EQ(error_of([] { load_mesh("/dev/zero"); }), "/dev/zero: cannot read mesh: not a regular file (character device)");
  EXPECT_EQ(error_of([] { fmpp::isect::read_triangles("/dev/zero"); }),
            "/dev/zero: cannot read triangle file: not a regular file (character device)");
  EXPECT_EQ(error_of([&] { fmpp::isect::read_rays(fifo); }), fifo + ": cannot read ray file: not a regular file (FIFO)");
}

TEST(HostileInput, SizeLimitsAreEnforcedBeforeReading) {
  const std::string big = dir() + "/big.json";
  { std::ofstream(big) << "{}"; }
  ASSERT_EQ(::truncate(big.c_str(), static_cast<off_t>(fmpp::isect::kMaxSceneBytes + 1)), 0);  // sparse
  EXPECT_EQ(error_of([&] { load_scene(big); }),
            big + ": cannot read scene: " + std::to_string(fmpp::isect::kMaxSceneBytes + 1) +
                " bytes, over the limit of " + std::to_string(fmpp::isect::kMaxSceneBytes));
}

TEST(HostileInput, NulBytesEndNothingSilently) {
  write("one.obj", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nf 1 2 3\n");
  write("nulpath.json", scene_for("one.obj\\u0000.x"));
  EXPECT_EQ(scene_error("nulpath.json"), dir() + "/nulpath.json: field 'meshes[0].file': the path holds a NUL byte");
  const std::string rays = write("nul.txt", std::string("0 0 0 0 0 1\n0 0 0 0 0 1\0" "5\n", 25));
  EXPECT_EQ(error_of([&] { fmpp::isect::read_rays(rays); }), rays + ":2: NUL byte (not a text file)");
  double x = 0;
  EXPECT_FALSE(fmpp::isect::parse_finite(std::string("1\0" "5", 3), &x));
  const std::string bom = write("bom.txt", "\xEF\xBB\xBF" "0 0 0 0 0 1\r\n1 1 1 0 0 1\r");
  EXPECT_EQ(fmpp::isect::read_rays(bom).size(), 2u);
}

TEST(HostileInput, MeshErrorsQuoteNothingFromTheFile) {
  const std::string secret = "root:x:0:0:SECRET-TOKEN:/root:/bin/bash\n";
  for (const char* ext : {"obj", "ply", "off", "stl", "gltf", "glb", "txt"}) {
    const std::string name = std::string("secret.") + ext;
    write(name, secret);
    write("secret.json", scene_for(name));
    const std::string e = scene_error("secret.json");
    EXPECT_NE(e, "no error") << ext;
    EXPECT_EQ(e.find("SECRET"), std::string::npos) << e;
    EXPECT_EQ(e.find("root:x"), std::string::npos) << e;
  }
}

TEST(HostileInput, LibraryLoopsEndInAnError) {
  // A reader that loops ends in the time limit (the child process is killed), well
  // before the loop would end by itself.
  const auto t0 = std::chrono::steady_clock::now();
  const auto loop = [] {
    for (int k = 0; k < 600; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    return std::string("no limit");
  };
  EXPECT_EQ(error_of([&] { run_isolated(loop, "x.ply: cannot read mesh", 2, kMeshReaderBytes); }),
            "x.ply: cannot read mesh: gave no result within 2 s");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 10);
  // An ASCII PLY header that assimp 5.2.5 looped on forever (found by fuzz_mesh): the
  // project reads PLY files itself, and names the line.
  const std::string path = std::string(FMPP_SOURCE_DIR) + "/tests/data/ply_header_loop.ply";
  EXPECT_EQ(error_of([&] { load_mesh(path); }), path + ":11: a property of unknown type");
  // An OFF face line that makes assimp's triangulation fail an assertion and abort when
  // the library's own validation step does not run first: the project reads OFF files
  // itself, and names the line and the index.
  const std::string off = std::string(FMPP_SOURCE_DIR) + "/tests/data/off_triangulate_abort.off";
  EXPECT_EQ(error_of([&] { load_mesh(off); }), off + ":7: face: index 3 is not a whole number");
}

TEST(HostileInput, RealMeshesInEveryFormat) {
  // Small meshes of Debian's libcgal-demo (make deps installs it), read from its archive.
  const std::string tar = "/usr/share/doc/libcgal-dev/data.tar.gz";
  const std::string cmd = "tar -xzf " + tar + " -C " + dir() +
                          " data/meshes/icosahedron.off data/meshes/colored_tetra.ply data/meshes/sphere.stl "
                          "data/meshes/sphere.ply";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const std::string m = dir() + "/data/meshes/";
  EXPECT_EQ(load_mesh(m + "icosahedron.off").triangles, 20u);
  EXPECT_EQ(load_mesh(m + "colored_tetra.ply").triangles, 4u);
  const Mesh stl = load_mesh(m + "sphere.stl"), ply = load_mesh(m + "sphere.ply");
  EXPECT_GT(stl.triangles, 100u);
  EXPECT_GT(ply.triangles, 100u);
  // glTF: the fuzz seed (its first byte picks the format).
  std::ifstream in(std::string(FMPP_SOURCE_DIR) + "/tests/fuzz/corpus/mesh/gltf_tri", std::ios::binary);
  const std::string seed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(seed.empty());
  const Mesh g = load_mesh(write("tri.gltf", seed.substr(1)));
  ASSERT_EQ(g.groups.size(), 1u);
  EXPECT_EQ(g.groups[0].name, "tri");
  EXPECT_EQ(g.triangles, 1u);
}

TEST(HostileInput, GltfFacesTheLibraryDropsAreAnError) {
  // Three triangles, the last with index 9 of 4 vertices: assimp drops that face and only
  // logs it; the loader makes its words an error naming the file.
  const std::string d = std::string(FMPP_SOURCE_DIR) + "/tests/data/";
  const std::string range = d + "gltf_index_out_of_range.gltf";
  EXPECT_EQ(error_of([&] { load_mesh(range); }),
            range + ": cannot read mesh: faces lost by the mesh library in meshes[0] primitive 0: 2 of 3 faces read "
                    "(Some faces had out-of-range indices. Those faces were dropped); fix the file");
  // A member of the wrong type: the library's message with its names, not "...".
  const std::string type = d + "gltf_member_type.gltf";
  EXPECT_EQ(error_of([&] { load_mesh(type); }),
            type + ": cannot read mesh: not a valid gltf file (Member \"indices\" was not of type \"uint\" when "
                   "reading meshes[0])");
  // A quoted token that is not a short name may be text of a file that is no mesh: "...".
  const std::string secret = write("secret.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [{\"primitives\": "
                                                  "[{\"attributes\": {\"POSITION\": \"root:x:0:0 secret\"}}]}]}");
  const std::string e = error_of([&] { load_mesh(secret); });
  EXPECT_EQ(e.find("root:x"), std::string::npos) << e;
}

}  // namespace
}  // namespace rt
