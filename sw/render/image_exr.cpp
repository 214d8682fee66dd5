// OpenEXR output (Debian's OpenEXR library): the linear radiance as 32-bit float RGB,
// encoded in memory and written atomically and checked like the PNG and PFM.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/util/output_file.h"
#include "sw/render/image.h"

namespace rt {

namespace {

// An OpenEXR output stream into a string.
class MemoryStream : public Imf::OStream {
 public:
  MemoryStream() : Imf::OStream("(memory)") {}
  void write(const char c[], int n) override {
    const size_t end = pos_ + static_cast<size_t>(n);
    if (end > data_.size()) data_.resize(end);
    std::memcpy(&data_[pos_], c, static_cast<size_t>(n));
    pos_ = end;
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = static_cast<size_t>(pos); }
  const std::string& data() const { return data_; }

 private:
  std::string data_;
  size_t pos_ = 0;
};

}  // namespace

void Image::write_exr(const std::string& path) const {
  std::vector<float> rgb(px_.size() * 3);
  for (size_t i = 0; i < px_.size(); ++i) {
    for (int c = 0; c < 3; ++c) rgb[3 * i + static_cast<size_t>(c)] = static_cast<float>(px_[i][c]);
  }
  MemoryStream stream;
  try {
    Imf::Header header(w_, h_);
    Imf::FrameBuffer fb;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgb.data() + c), 3 * sizeof(float),
                                     3 * sizeof(float) * static_cast<size_t>(w_)));
    }
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(fb);
    file.writePixels(h_);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": cannot encode OpenEXR: " + e.what());
  }
  fmpp::write_output(path, stream.data());
}

}  // namespace rt
