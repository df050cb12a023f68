// Contact problems on file (cd/problem_file.h). Layout: a magic line, the sizes of Contact and
// BodyVelocity, the label's length and text, the contact and body counts, then the raw arrays.
#include "cd/problem_file.h"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <stdexcept>

namespace cd {

namespace {

constexpr char magic[8] = {'C', 'D', 'P', 'R', 'O', 'B', '1', '\n'};

struct Header {
  std::uint32_t contact_size = sizeof(Contact);
  std::uint32_t velocity_size = sizeof(BodyVelocity);
  std::uint64_t label_size = 0;
  std::uint64_t contact_count = 0;
  std::uint64_t body_count = 0;
};

template <class T>
void write_array(std::ofstream& out, const std::vector<T>& values)
{
  out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(T)));
}

class ProblemReader {
 public:
  explicit ProblemReader(const std::string& path) : path_(path), in_(path, std::ios::binary)
  {
    if (!in_) fail("cannot be opened");
  }

  [[noreturn]] void fail(const std::string& what) const
  {
    throw std::runtime_error("contact problem " + path_ + ": " + what);
  }

  void read(void* to, std::size_t bytes, const char* what)
  {
    in_.read(static_cast<char*>(to), static_cast<std::streamsize>(bytes));
    if (static_cast<std::size_t>(in_.gcount()) != bytes) fail(std::string("truncated in its ") + what);
  }

  template <class T>
  void read_array(std::vector<T>& values, std::uint64_t count, const char* what)
  {
    values.resize(count);
    read(values.data(), count * sizeof(T), what);
  }

  bool at_end() { return in_.peek() == std::char_traits<char>::eof(); }

 private:
  std::string path_;
  std::ifstream in_;
};

}  // namespace

void write_problem(const std::string& path, const ContactProblem& problem)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  Header header;
  header.label_size = problem.label.size();
  header.contact_count = problem.contacts.size();
  header.body_count = problem.free_velocity.size();
  out.write(magic, sizeof(magic));
  out.write(reinterpret_cast<const char*>(&header), sizeof(header));
  out.write(problem.label.data(), static_cast<std::streamsize>(problem.label.size()));
  write_array(out, problem.contacts);
  write_array(out, problem.free_velocity);
  write_array(out, problem.height);
  if (!out) throw std::runtime_error("contact problem " + path + ": cannot be written");
}

ContactProblem read_problem(const std::string& path)
{
  ProblemReader in(path);
  char found[sizeof(magic)];
  in.read(found, sizeof(found), "magic line");
  if (!std::equal(found, found + sizeof(found), magic)) in.fail("not a contact problem file");
  Header header;
  in.read(&header, sizeof(header), "header");
  if (header.contact_size != sizeof(Contact) || header.velocity_size != sizeof(BodyVelocity))
    in.fail("written by a build with another Contact layout");
  ContactProblem problem;
  problem.label.resize(header.label_size);
  in.read(problem.label.data(), header.label_size, "label");
  in.read_array(problem.contacts, header.contact_count, "contacts");
  in.read_array(problem.free_velocity, header.body_count, "velocities");
  in.read_array(problem.height, header.body_count, "heights");
  if (!in.at_end()) in.fail("longer than its header says");
  for (const Contact& c : problem.contacts)
    if (c.body_a < 0 || c.body_b < 0 || static_cast<std::uint64_t>(std::max(c.body_a, c.body_b)) >= header.body_count)
      in.fail("a contact names a body out of range");
  return problem;
}

}  // namespace cd
