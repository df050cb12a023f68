// The local problem of a saved step, and its FCLIB file (bench/peers/local_problem.h).
#include "local_problem.h"

#include <hdf5.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <utility>

extern "C" {
#include <fclib.h>
}

namespace peers {

namespace {

// Contacts touching each body; the world's (body 0) are left out: its velocity never changes.
std::vector<std::vector<int>> contacts_of_bodies(const std::vector<cd::Contact>& contacts, std::size_t bodies)
{
  std::vector<std::vector<int>> of_body(bodies);
  for (std::size_t k = 0; k < contacts.size(); k++) {
    const cd::Contact& c = contacts[k];
    if (c.body_a > 0) of_body[c.body_a].push_back(static_cast<int>(k));
    if (c.body_b > 0 && c.body_b != c.body_a) of_body[c.body_b].push_back(static_cast<int>(k));
  }
  return of_body;
}

// Column `column` of W (SI): the local velocities every contact sees after a unit impulse
// along `unit` at contact j, as the core's apply_impulse and relative_velocity make them.
std::vector<std::pair<int, double>> delassus_column(const std::vector<cd::Contact>& contacts,
                                                    const std::vector<std::vector<int>>& of_body, int j,
                                                    cd::Local2 unit, std::vector<cd::BodyVelocity>& change)
{
  const cd::Contact& c = contacts[j];
  cd::apply_impulse(c, unit, change[c.body_a], change[c.body_b]);
  std::vector<int> touched;
  for (const int body : {c.body_a, c.body_b})
    if (body > 0) touched.insert(touched.end(), of_body[body].begin(), of_body[body].end());
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  std::vector<std::pair<int, double>> column;
  for (const int k : touched) {
    const cd::Contact& other = contacts[k];
    const cd::Local2 u = cd::relative_velocity(other, change[other.body_a], change[other.body_b]);
    if (u.n != 0.0) column.emplace_back(2 * k, u.n);
    if (u.t != 0.0) column.emplace_back(2 * k + 1, u.t);
  }
  change[c.body_a] = {};
  change[c.body_b] = {};
  return column;
}

double mean_normal_stiffness(const std::vector<cd::Contact>& contacts)
{
  double sum = 0.0;
  for (const cd::Contact& c : contacts) sum += c.delassus.nn;
  return contacts.empty() || !(sum > 0.0) ? 1.0 : sum / static_cast<double>(contacts.size());
}

[[noreturn]] void refuse(const std::string& path, const std::string& what)
{
  throw std::runtime_error("FCLIB problem " + path + ": " + what);
}

constexpr const char* scale_key = "impulse scale s (m/s per N s): ";

std::string describe_scale(double scale)
{
  char text[64];
  std::snprintf(text, sizeof(text), "%.17g", scale);
  return std::string(scale_key) + text;
}

double scale_of(const char* description)
{
  if (!description) return 1.0;
  const std::string text(description);
  const auto at = text.find(scale_key);
  return at == std::string::npos ? 1.0 : std::strtod(text.c_str() + at + std::string(scale_key).size(), nullptr);
}

struct FclibLocalDeleter {
  void operator()(fclib_local* p) const { fclib_delete_local(p); }
};

bool is_hdf5(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  char signature[8] = {};
  in.read(signature, sizeof(signature));
  return in && std::equal(signature, signature + 8, "\x89HDF\r\n\x1a\n");
}

void check_matrix(const std::string& path, const fclib_matrix* w, int size)
{
  if (!w) refuse(path, "no matrix W");
  if (w->m != size || w->n != size)
    refuse(path, "W is " + std::to_string(w->m) + " x " + std::to_string(w->n) + ", expected " + std::to_string(size) +
                     " x " + std::to_string(size));
  if (w->nz != -1) refuse(path, "W is not stored by compressed columns");
  if (w->p[0] != 0 || w->p[size] < 0 || w->p[size] > w->nzmax) refuse(path, "W's column pointers are inconsistent");
  for (int j = 0; j < size; j++) {
    if (w->p[j + 1] < w->p[j]) refuse(path, "W's column pointers decrease");
    for (int e = w->p[j]; e < w->p[j + 1]; e++)
      if (w->i[e] < 0 || w->i[e] >= size) refuse(path, "W has a row index out of range");
  }
}

}  // namespace

bool same_problem(const LocalProblem& a, const LocalProblem& b)
{
  return a.contacts == b.contacts && a.column_start == b.column_start && a.row == b.row && a.value == b.value &&
         a.q == b.q && a.mu == b.mu && a.warm_start == b.warm_start;
}

std::vector<double> LocalProblem::velocity(const std::vector<double>& reaction) const
{
  std::vector<double> u = q;
  for (int j = 0; j < size(); j++)
    for (int e = column_start[j]; e < column_start[j + 1]; e++) u[row[e]] += value[e] * reaction[j];
  return u;
}

LocalProblem local_problem(const cd::ContactProblem& problem)
{
  LocalProblem local;
  const std::vector<cd::Contact>& contacts = problem.contacts;
  local.contacts = static_cast<int>(contacts.size());
  local.label = problem.label;
  local.impulse_scale = mean_normal_stiffness(contacts);
  const auto of_body = contacts_of_bodies(contacts, problem.free_velocity.size());
  std::vector<cd::BodyVelocity> change(problem.free_velocity.size());
  local.column_start.push_back(0);
  for (int j = 0; j < local.contacts; j++)
    for (const cd::Local2 unit : {cd::Local2{1.0, 0.0}, cd::Local2{0.0, 1.0}}) {
      for (const auto& [r, w] : delassus_column(contacts, of_body, j, unit, change)) {
        local.row.push_back(r);
        local.value.push_back(w / local.impulse_scale);
      }
      local.column_start.push_back(static_cast<int>(local.row.size()));
    }
  for (const cd::Contact& c : contacts) {
    const cd::Local2 u = cd::law_velocity(c, problem.free_velocity[c.body_a], problem.free_velocity[c.body_b]);
    local.q.insert(local.q.end(), {u.n, u.t});
    local.mu.push_back(c.mu);
  }
  local.warm_start = reaction_of(local, contacts);
  return local;
}

std::vector<double> reaction_of(const LocalProblem& local, const std::vector<cd::Contact>& contacts)
{
  std::vector<double> r;
  r.reserve(2 * contacts.size());
  for (const cd::Contact& c : contacts)
    r.insert(r.end(), {local.impulse_scale * c.impulse.n, local.impulse_scale * c.impulse.t});
  return r;
}

void write_fclib(const std::string& path, const LocalProblem& p)
{
  // FCLIB's structures hold non-const pointers; they are only read while writing.
  std::vector<int> column_start = p.column_start, row = p.row;
  std::vector<double> value = p.value, q = p.q, mu = p.mu, r0 = p.warm_start, u0 = p.velocity(p.warm_start);
  std::string title = p.label, description = describe_scale(p.impulse_scale), math = "2D local problem";
  fclib_matrix w{};
  w.nzmax = static_cast<int>(value.size());
  w.m = w.n = p.size();
  w.p = column_start.data();
  w.i = row.data();
  w.x = value.data();
  w.nz = -1;
  fclib_info info{title.data(), description.data(), math.data()};
  fclib_local local{};
  local.W = &w;
  local.mu = mu.data();
  local.q = q.data();
  local.spacedim = 2;
  local.info = &info;
  std::remove(path.c_str());
  fclib_solution guess{nullptr, u0.data(), r0.data(), nullptr};
  if (!fclib_write_local(&local, path.c_str()) || !fclib_write_guesses(1, &guess, path.c_str()))
    refuse(path, "cannot be written");
}

LocalProblem read_fclib(const std::string& path)
{
  if (!std::ifstream(path)) refuse(path, "cannot be opened");
  if (!is_hdf5(path)) refuse(path, "not an HDF5 file");
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // a malformed file gets our one line, not HDF5's trace
  std::unique_ptr<fclib_local, FclibLocalDeleter> local(fclib_read_local(path.c_str()));
  if (!local) refuse(path, "not an FCLIB local problem");
  if (local->spacedim != 2) refuse(path, "spacedim " + std::to_string(local->spacedim) + ", expected 2");
  if (local->V || local->R || local->s) refuse(path, "has V, R or s (a mixed problem), not supported");
  if (!local->W || local->W->m % 2 != 0) refuse(path, "W's size is not twice a contact count");
  LocalProblem p;
  p.contacts = local->W->m / 2;
  check_matrix(path, local->W, p.size());
  if (!local->q || !local->mu) refuse(path, "no q or mu");
  const int nnz = local->W->p[p.size()];
  p.column_start.assign(local->W->p, local->W->p + p.size() + 1);
  p.row.assign(local->W->i, local->W->i + nnz);
  p.value.assign(local->W->x, local->W->x + nnz);
  p.q.assign(local->q, local->q + p.size());
  p.mu.assign(local->mu, local->mu + p.contacts);
  if (local->info) {
    p.label = local->info->title ? local->info->title : "";
    p.impulse_scale = scale_of(local->info->description);
  }
  int guesses = 0;
  fclib_solution* guess = fclib_read_guesses(path.c_str(), &guesses);
  if (guess && guesses > 0 && guess[0].r) p.warm_start.assign(guess[0].r, guess[0].r + p.size());
  else p.warm_start.assign(p.size(), 0.0);
  if (guess) fclib_delete_solutions(guess, guesses);
  return p;
}

}  // namespace peers
