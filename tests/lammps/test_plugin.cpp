// The plugin registers the same styles through LAMMPS's plugin interface, and its creator
// builds a working fix (Debian's lmp lacks `plugin load`, so the test plays the loader's part).
#include <gtest/gtest.h>

#include <dlfcn.h>

#include <string>
#include <vector>

#include "lammps_session.h"
#include "lammpsplugin.h"
#include "version.h"

#ifndef CD_PLUGIN_PATH
#error "CD_PLUGIN_PATH must name the plugin"
#endif

namespace {

std::vector<lammpsplugin_t> registered;

void record_registration(lammpsplugin_t* plugin, void*)
{
  registered.push_back(*plugin);
}

TEST(Plugin, RegistersContactDynamicsAndItsCreatorRuns)
{
  void* handle = dlopen(CD_PLUGIN_PATH, RTLD_NOW | RTLD_LOCAL);
  ASSERT_NE(handle, nullptr) << dlerror();
  auto init = reinterpret_cast<lammpsplugin_initfunc>(dlsym(handle, "lammpsplugin_init"));
  ASSERT_NE(init, nullptr);

  cdtest::LammpsSession s;
  registered.clear();
  init(s.lmp, handle, reinterpret_cast<void*>(&record_registration));
  ASSERT_EQ(registered.size(), 1u);
  EXPECT_STREQ(registered[0].style, "fix");
  EXPECT_STREQ(registered[0].name, "contact/dynamics");
  EXPECT_STREQ(registered[0].version, LAMMPS_VERSION);

  // What `plugin load` does with a fix creator.
  (*s.lmp->modify->fix_map)["contact/dynamics/plugin"] =
      reinterpret_cast<LAMMPS_NS::Modify::FixCreator>(registered[0].creator.v2);
  s.commands(cdtest::disk_preamble);
  s.commands(R"(
boundary p f p
region box block 0 0.01 0 0.01 -0.0003 0.0003
create_box 1 box
create_atoms 1 single 0.005 0.001 0
set group all diameter 5e-4 density/disc 2500
neighbor 1e-4 bin
timestep 1e-5
fix grav all gravity 9.81 vector 0 -1 0
fix cd all contact/dynamics/plugin 0.5 0.0 wall yplane 0.0 0.5 0.0
fix 2d all enforce2d
run 5000
)");
  // Fell 0.75 mm onto the floor with e = 0 and came to rest on it.
  EXPECT_NEAR(s.x(1, 1), 2.5e-4, 1e-9);
  EXPECT_NEAR(s.v(1, 1), 0.0, 1e-9);
  dlclose(handle);
}

}  // namespace
