// Line-by-line reading of plain or gzip-compressed text files, with the position kept
// for error messages ("file:line: problem").
#pragma once

#include <stdexcept>
#include <string>

namespace cdpost {

// A problem with an input file. what() is one line: "FILE:LINE: PROBLEM" (or "FILE: PROBLEM"
// when no line applies).
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, long line, const std::string& problem);
};

// Reads a text file one line at a time; gzip input is detected from the data, not the name.
// The file is streamed: only the current line is held in memory. A line holding a NUL or another
// control byte (a binary file, or gzip of one) fails in one line that does not echo its bytes.
class LineSource {
 public:
  explicit LineSource(const std::string& path);
  ~LineSource();
  LineSource(const LineSource&) = delete;
  LineSource& operator=(const LineSource&) = delete;

  // Reads the next line without its end-of-line characters; false at the end of the file.
  bool next(std::string& line);
  long line_number() const { return line_number_; }
  const std::string& path() const { return path_; }
  // Fraction of the (compressed) file consumed so far, for progress display.
  double fraction_read() const;

  [[noreturn]] void fail(const std::string& problem) const;

 private:
  void check_stream() const;

  std::string path_;
  void* file_ = nullptr;  // gzFile, kept opaque so zlib stays out of this header
  long line_number_ = 0;
  double file_size_bytes_ = 0;
};

}  // namespace cdpost
