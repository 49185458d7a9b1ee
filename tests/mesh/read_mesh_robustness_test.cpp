// SPDX-License-Identifier: GPL-3.0-or-later
// Robustness of read_mesh on damaged real files of every format: truncated
// at many lengths, bit-flipped, and random bytes behind a valid header.
// Every read must either give a usable mesh (faces, indices in range, finite
// coordinates) or throw a subfab::Error: never another exception, a crash,
// a hang, or an out-of-bounds read (this test also runs under ASan/UBSan).
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include "subfab/core/error.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

std::string load(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

//! Length of the part of the file that we keep intact in the random-bytes
//! variants: the PLY header, the OFF/OBJ first lines, the binary STL header.
std::size_t header_length(const std::string& bytes, const std::string& ext) {
  if (ext == ".ply") {
    const auto end = bytes.find("end_header");
    return end == std::string::npos ? 0 : bytes.find('\n', end) + 1;
  }
  if (ext == ".stl") return bytes.compare(0, 5, "solid") == 0 ? bytes.find('\n') + 1 : 84;
  // OBJ / OFF: the first two lines (OFF keyword and counts, or OBJ comment / first vertex).
  const auto first = bytes.find('\n');
  return bytes.find('\n', first + 1) + 1;
}

constexpr int kNumFlipVariants = 150;
constexpr int kNumRandomVariants = 40;

class DamagedFiles : public ::testing::TestWithParam<const char*> {
 protected:
  //! Writes the variant and reads it; counts the outcomes.
  void check(const std::string& bytes, const std::string& what) {
    // A new file each time (rewriting one file in place makes ext4 flush it
    // to disk on close, which is slow); removed after reading.
    const auto path = dir_ / ("variant" + std::to_string(num_read_ + num_refused_) + ext_);
    {
      std::ofstream out(path, std::ios::binary);
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    }
    struct Remove {
      std::filesystem::path path;
      ~Remove() { std::filesystem::remove(path); }
    } remove_after{path};
    try {
      const Mesh mesh = read_mesh(path);
      ++num_read_;
      ASSERT_FALSE(mesh.faces.empty()) << what;
      for (const auto& t : mesh.faces)
        for (int v : t) ASSERT_TRUE(v >= 0 && static_cast<std::size_t>(v) < mesh.num_vertices()) << what;
      for (const auto& p : mesh.vertices) ASSERT_TRUE(p.allFinite()) << what;
    } catch (const Error& e) {
      ++num_refused_;
      ASSERT_GT(std::string(e.what()).size(), 10u) << what;
    } catch (const std::exception& e) {
      FAIL() << what << ": exception that is not a subfab::Error: " << e.what();
    }
  }

  void SetUp() override {
    source_ = test::data_path(GetParam());
    ext_ = source_.extension().string();
    original_ = load(source_);
    ASSERT_GT(original_.size(), 100u);
    dir_ = test::temp_dir();
  }

  std::filesystem::path source_, dir_;
  std::string ext_, original_;
  std::mt19937 rng_{20240607};  // fixed seed: the same variants every run
  std::size_t num_read_ = 0, num_refused_ = 0;
};

TEST_P(DamagedFiles, Truncated) {
  const std::size_t n = original_.size();
  std::vector<std::size_t> lengths;
  for (std::size_t len = 0; len < std::min<std::size_t>(n, 200); len += 7) lengths.push_back(len);  // headers
  for (std::size_t k = 1; k < 100; ++k) lengths.push_back(n * k / 100);
  for (std::size_t len = n - std::min<std::size_t>(n, 30); len < n; len += 3) lengths.push_back(len);  // the end
  for (std::size_t len : lengths) check(original_.substr(0, len), "truncated at " + std::to_string(len));
  EXPECT_GT(num_refused_, 0u);
}

TEST_P(DamagedFiles, BitFlipped) {
  for (int variant = 0; variant < kNumFlipVariants; ++variant) {
    std::string bytes = original_;
    const int num_flips = 1 + static_cast<int>(rng_() % 8);
    // Half the variants flip bits in the first 512 bytes (headers, counts).
    const std::size_t range = variant % 2 == 0 ? std::min<std::size_t>(bytes.size(), 512) : bytes.size();
    for (int f = 0; f < num_flips; ++f) bytes[rng_() % range] ^= static_cast<char>(1u << (rng_() % 8));
    check(bytes, "bit-flip variant " + std::to_string(variant));
  }
  EXPECT_EQ(num_read_ + num_refused_, static_cast<std::size_t>(kNumFlipVariants));
}

TEST_P(DamagedFiles, RandomBytesAfterAValidHeader) {
  const std::size_t keep = header_length(original_, ext_);
  ASSERT_LT(keep, original_.size());
  for (int variant = 0; variant < kNumRandomVariants; ++variant) {
    std::string bytes = original_.substr(0, keep);
    const std::size_t body = variant % 2 == 0 ? original_.size() - keep : rng_() % 4096;
    // Even variants: any byte. Odd: digits, signs, spaces and newlines, which
    // look like text records and go deeper into the text parsers.
    static const char kTextish[] = "0123456789-. \n/evf";
    for (std::size_t i = 0; i < body; ++i)
      bytes += variant % 2 == 0 ? static_cast<char>(rng_() & 0xff) : kTextish[rng_() % (sizeof kTextish - 1)];
    check(bytes, "random-body variant " + std::to_string(variant));
  }
  EXPECT_EQ(num_read_ + num_refused_, static_cast<std::size_t>(kNumRandomVariants));
}

INSTANTIATE_TEST_SUITE_P(Files, DamagedFiles,
                         ::testing::Values("spot.obj", "cow.obj", "decimated_knight.off", "cross.off",
                                           "formats/cross_ascii.ply", "formats/part_binary_le.ply",
                                           "formats/knight_binary_be.ply", "formats/part_tristrips.ply",
                                           "formats/part_ascii.stl", "formats/knight_binary.stl",
                                           "formats/cross_binary_solid.stl"),
                         [](const auto& param_info) {
                           std::string name = param_info.param;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace subfab
