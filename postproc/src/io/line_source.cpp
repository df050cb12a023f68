#include "io/line_source.h"

#include <zlib.h>

#include <cstring>

#include <sys/stat.h>

namespace cdpost {

namespace {
std::string position(const std::string& file, long line)
{
  return line > 0 ? file + ":" + std::to_string(line) + ": " : file + ": ";
}
gzFile as_gz(void* file)
{
  return static_cast<gzFile>(file);
}
// A control byte other than tab, newline and carriage return: not in a LAMMPS text file.
bool has_control_byte(const char* text, size_t length)
{
  for (size_t i = 0; i < length; ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if ((byte < 0x20 && byte != '\t' && byte != '\n' && byte != '\r') || byte == 0x7f) return true;
  }
  return false;
}
}  // namespace

InputError::InputError(const std::string& file, long line, const std::string& problem)
    : std::runtime_error(position(file, line) + problem)
{
}

LineSource::LineSource(const std::string& path) : path_(path)
{
  struct stat info {};
  if (stat(path.c_str(), &info) != 0) throw InputError(path, 0, "cannot open (no such file)");
  if (S_ISDIR(info.st_mode)) throw InputError(path, 0, "is a directory, not a file");
  file_size_bytes_ = static_cast<double>(info.st_size);
  file_ = gzopen(path.c_str(), "rb");
  if (!file_) throw InputError(path, 0, "cannot open for reading");
  gzbuffer(as_gz(file_), 1 << 18);
}

LineSource::~LineSource()
{
  if (file_) gzclose(as_gz(file_));
}

bool LineSource::next(std::string& line)
{
  line.clear();
  char buffer[4096];
  bool got_any = false;
  while (true) {
    const z_off_t before = gztell(as_gz(file_));
    if (!gzgets(as_gz(file_), buffer, sizeof buffer)) break;
    // gzgets stops at a newline, not at a NUL: fewer characters than bytes read means a NUL.
    const size_t length = std::strlen(buffer);
    if (static_cast<z_off_t>(length) != gztell(as_gz(file_)) - before || has_control_byte(buffer, length))
      throw InputError(path_, line_number_ + 1,
                       "binary data, not text: cdpost reads LAMMPS text output, plain or gzip-compressed "
                       "(write dumps with dump custom, not a binary .bin dump)");
    got_any = true;
    line.append(buffer, length);
    if (!line.empty() && line.back() == '\n') break;
  }
  // A line without its newline is the last one: make sure it is not cut by a broken stream.
  if (!got_any || line.back() != '\n') check_stream();
  if (!got_any) return false;
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  ++line_number_;
  return true;
}

void LineSource::check_stream() const
{
  int code = Z_OK;
  gzgetc(as_gz(file_));  // forces the decompressor to the end, where truncation shows
  const char* message = gzerror(as_gz(file_), &code);
  if (code != Z_OK && code != Z_STREAM_END)
    throw InputError(path_, line_number_ + 1, std::string("corrupt or truncated compressed data (") + message + ")");
}

double LineSource::fraction_read() const
{
  if (file_size_bytes_ <= 0) return 1.0;
  return static_cast<double>(gzoffset(as_gz(file_))) / file_size_bytes_;
}

void LineSource::fail(const std::string& problem) const
{
  throw InputError(path_, line_number_, problem);
}

}  // namespace cdpost
