#include "formats/image_io.h"

#include <gtest/gtest.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <random>
#include <vector>

#include "formats/atomic_file.h"
#include "scene/error.h"

namespace rad {
namespace {

std::filesystem::path temp_dir() {
  const auto dir =
      std::filesystem::temp_directory_path() /
      ("rad_viz_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
       ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::remove_all(dir);  // a fresh folder per test, whatever an earlier run left
  std::filesystem::create_directories(dir);
  return dir;
}

Image random_image(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 100);
  Image image(w, h);
  for (Rgb& p : image.pixels) p = Rgb(u(rng), u(rng), u(rng));
  return image;
}

TEST(ImageIo, ExrRoundTripKeepsFloatValues) {
  const Image image = random_image(37, 23, 1);
  const auto file = temp_dir() / "round.exr";
  write_exr(file, image);
  const Image back = read_exr(file);
  ASSERT_EQ(back.width, 37);
  ASSERT_EQ(back.height, 23);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(back.pixels[i][c], static_cast<double>(static_cast<float>(image.pixels[i][c])))
          << i;
    }
  }
}

TEST(ImageIo, ReadingMissingOrBogusExrNamesTheFile) {
  const auto dir = temp_dir();
  EXPECT_THROW(read_exr(dir / "missing.exr"), InputError);
  std::ofstream(dir / "bogus.exr") << "not an exr";
  try {
    read_exr(dir / "bogus.exr");
    FAIL() << "bogus file accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bogus.exr"), std::string::npos) << e.what();
  }
}

/// `file` with the data window of its header (the box2i after "dataWindow") set to the given
/// corners: a header claiming an image the file does not hold.
void set_data_window(const std::filesystem::path& file, int32_t max_x, int32_t max_y) {
  std::ifstream in(file, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  in.close();
  const std::string key("dataWindow\0box2i\0", 17);
  const size_t at = bytes.find(key);
  ASSERT_NE(at, std::string::npos);
  // After the key: the attribute's size (16), then min.x, min.y, max.x, max.y.
  std::memcpy(bytes.data() + at + key.size() + 4 + 8, &max_x, 4);
  std::memcpy(bytes.data() + at + key.size() + 4 + 12, &max_y, 4);
  std::ofstream(file, std::ios::binary) << bytes;
}

std::string read_error(const std::filesystem::path& file) {
  try {
    read_exr(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ImageIo, ExrClaimingMorePixelsThanItHoldsIsRefusedBeforeAllocating) {
  const auto dir = temp_dir();
  write_exr(dir / "small.exr", random_image(4, 4, 2));
  EXPECT_EQ(read_error(dir / "small.exr"), "") << "the untouched file must read";
  // A constant image is ZIP's best case: the densest file `render` can write must still read.
  write_exr(dir / "constant.exr", Image(2048, 2048));
  EXPECT_EQ(read_error(dir / "constant.exr"), "")
      << std::filesystem::file_size(dir / "constant.exr") << " bytes";
  // Beyond the side limit, before OpenEXR sizes its offset tables from it.
  std::filesystem::copy_file(dir / "small.exr", dir / "wide.exr");
  set_data_window(dir / "wide.exr", 100'000, 3);
  EXPECT_NE(read_error(dir / "wide.exr").find("wide.exr: part 0 claims an image of 100001 x 4"),
            std::string::npos)
      << read_error(dir / "wide.exr");
  // 4 x 32768 ZIP scan lines need 2048 chunk offsets: more than a 521-byte file holds.
  std::filesystem::copy_file(dir / "small.exr", dir / "tall.exr");
  set_data_window(dir / "tall.exr", 3, 32767);
  EXPECT_NE(read_error(dir / "tall.exr").find("implies 2048 chunks"), std::string::npos)
      << read_error(dir / "tall.exr");
  // An attribute whose size claims 2 GB (OpenEXR would allocate it before reading).
  {
    std::ifstream in(dir / "small.exr", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    const std::string key("compression\0compression\0", 24);
    const size_t at = bytes.find(key);
    ASSERT_NE(at, std::string::npos);
    const int32_t huge = 0x7fffffff;
    std::memcpy(bytes.data() + at + key.size(), &huge, 4);
    std::ofstream(dir / "attribute.exr", std::ios::binary) << bytes;
  }
  EXPECT_NE(read_error(dir / "attribute.exr")
                .find("header attribute \"compression\" claims 2147483647 bytes"),
            std::string::npos)
      << read_error(dir / "attribute.exr");
  // Within the side limit, 8000 x 8000 from a file that holds 4 x 8000 zeros (so that it has
  // the table of chunk offsets OpenEXR reads first): a few kilobytes claiming 2 GiB.
  write_exr(dir / "claims.exr", Image(4, 8000));
  set_data_window(dir / "claims.exr", 7999, 7999);
  EXPECT_NE(read_error(dir / "claims.exr").find("an image of 8000 x 8000 x 3 channels would take"),
            std::string::npos)
      << read_error(dir / "claims.exr");
  // Channels beyond the limit.
  ChannelImage many{1, 1, {}};
  for (int c = 0; c <= 64; ++c) many.channels[std::to_string(100 + c)] = {1.0f};
  write_exr_channels(dir / "many.exr", many);
  EXPECT_NE(read_error(dir / "many.exr").find("65 channels, more than 64"), std::string::npos)
      << read_error(dir / "many.exr");
}

TEST(ImageIo, SrgbEncodingMatchesTheStandard) {
  EXPECT_EQ(to_srgb8(0.0, 0), 0);
  EXPECT_EQ(to_srgb8(1.0, 0), 255);
  EXPECT_EQ(to_srgb8(7.0, 0), 255);  // clamped
  EXPECT_EQ(to_srgb8(-1.0, 0), 0);
  EXPECT_EQ(to_srgb8(0.5, 0), 188);   // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354
  EXPECT_EQ(to_srgb8(0.25, 1), 188);  // one stop up
  EXPECT_EQ(to_srgb8(0.002, 0), 7);   // linear segment: 12.92 * 0.002 * 255 = 6.6
}

TEST(ImageIo, AutoExposureMakesThe95thPercentileWhite) {
  // 1, 2, ..., 100: the 95th percentile (index 0.95 * 99, rounded down) is 95.
  std::vector<double> values;
  for (int i = 1; i <= 100; ++i) values.push_back(i);
  EXPECT_DOUBLE_EQ(auto_exposure(values), -std::log2(95.0));
  EXPECT_EQ(to_srgb8(95, auto_exposure(values)), 255);
  EXPECT_LT(to_srgb8(94, auto_exposure(values)), 255);
  // Black, NaN and negative values are not part of the picture's range: a few lit pixels on
  // black get the exposure of their own values.
  values.insert(values.end(), 1000, 0.0);
  values.push_back(std::nan(""));
  values.push_back(-5);
  EXPECT_DOUBLE_EQ(auto_exposure(values), -std::log2(95.0));
  EXPECT_EQ(auto_exposure(std::vector<double>(10, 0.0)), 0);
  // An image: each pixel's brightest channel.
  Image image(2, 1);
  image.at(0, 0) = Rgb(0.5, 4, 1);
  image.at(1, 0) = Rgb(0, 0, 0);
  EXPECT_DOUBLE_EQ(auto_exposure(image), -2);
}

TEST(ImageIo, PngPreviewIsTopDownAndEncoded) {
  Image image(4, 3);
  image.at(0, 0) = Rgb(1, 0, 0);    // top-left red
  image.at(3, 2) = Rgb(0, 0, 0.5);  // bottom-right mid blue
  const auto file = temp_dir() / "preview.png";
  write_png_preview(file, image);
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkImageData* data = reader->GetOutput();
  int dims[3];
  data->GetDimensions(dims);
  ASSERT_EQ(dims[0], 4);
  ASSERT_EQ(dims[1], 3);
  ASSERT_EQ(data->GetNumberOfScalarComponents(), 3);
  // VTK row 0 is the bottom: top-left is (0, 2).
  auto* top_left = static_cast<unsigned char*>(data->GetScalarPointer(0, 2, 0));
  EXPECT_EQ(top_left[0], 255);
  EXPECT_EQ(top_left[1], 0);
  auto* bottom_right = static_cast<unsigned char*>(data->GetScalarPointer(3, 0, 0));
  EXPECT_EQ(bottom_right[2], 188);
}

TEST(AtomicFile, LeavesTargetUntouchedUntilCommit) {
  const auto dir = temp_dir();
  const auto target = dir / "result.exr";
  std::ofstream(target) << "precious";
  {
    AtomicFile out(target);
    std::ofstream(out.temp_path()) << "half-written";
    EXPECT_TRUE(std::filesystem::exists(out.temp_path()));
    // no commit: as if writing threw
  }
  std::ifstream in(target);
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(content, "precious");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1)
      << "temp file left behind";
  {
    AtomicFile out(target);
    std::ofstream(out.temp_path()) << "new";
    out.commit();
  }
  std::ifstream again(target);
  std::string updated((std::istreambuf_iterator<char>(again)), std::istreambuf_iterator<char>());
  EXPECT_EQ(updated, "new");
}

TEST(AtomicFile, WriteTextFileReplacesOnlyOnSuccess) {
  const auto dir = temp_dir();
  const auto target = dir / "out.csv";
  std::ofstream(target) << "precious";
  EXPECT_THROW(write_text_file(target,
                               [](std::ostream& out) {
                                 out << "half";
                                 throw Error("writer failed");
                               }),
               Error);
  const auto read = [&] {
    std::ifstream in(target);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  EXPECT_EQ(read(), "precious");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1)
      << "temp file left behind";
  write_text_file(target, [](std::ostream& out) { out << "new\n"; });
  EXPECT_EQ(read(), "new\n");
}

TEST(AtomicFile, CreatesMissingFolders) {
  const auto target = temp_dir() / "a/b/c.exr";
  write_exr(target, random_image(2, 2, 3));
  EXPECT_TRUE(std::filesystem::exists(target));
}

TEST(AtomicFile, TemporariesAreUniqueAndKeepTheExtension) {
  const auto target = temp_dir() / "r.exr";
  AtomicFile a(target), b(target);
  EXPECT_NE(a.temp_path(), b.temp_path());
  EXPECT_EQ(a.temp_path().extension(), ".exr");
  EXPECT_EQ(a.temp_path().parent_path(), target.parent_path());
}

TEST(CommitGroup, RenamesAllOrNone) {
  const auto dir = temp_dir();
  const auto read = [](const std::filesystem::path& p) {
    std::ifstream in(p);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  std::ofstream(dir / "a.csv") << "old a";
  std::ofstream(dir / "b.csv") << "old b";
  const auto write_both = [&](bool fail_second) {
    CommitGroup group;
    write_text_file(dir / "a.csv", [](std::ostream& out) { out << "new a"; });
    EXPECT_EQ(read(dir / "a.csv"), "old a");  // committed, but the group holds the rename
    write_text_file(dir / "b.csv", [&](std::ostream& out) {
      if (fail_second) throw Error("disk full");
      out << "new b";
    });
    group.commit();
  };
  EXPECT_THROW(write_both(true), Error);
  EXPECT_EQ(read(dir / "a.csv"), "old a");
  EXPECT_EQ(read(dir / "b.csv"), "old b");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 2)
      << "temp file left behind";
  write_both(false);
  EXPECT_EQ(read(dir / "a.csv"), "new a");
  EXPECT_EQ(read(dir / "b.csv"), "new b");
}

}  // namespace
}  // namespace rad
