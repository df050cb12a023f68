// Plugin entry point for `plugin load` in a PLUGIN-enabled LAMMPS of the same version.
#include "lammpsplugin.h"
#include "style_registry.h"
#include "version.h"

extern "C" void lammpsplugin_init(void* lmp, void* handle, void* regfunc)
{
  auto register_style = reinterpret_cast<lammpsplugin_regfunc>(regfunc);
  int count = 0;
  const LAMMPS_NS::FixStyleEntry* styles = LAMMPS_NS::project_fix_styles(count);
  for (int k = 0; k < count; k++) {
    lammpsplugin_t plugin;
    plugin.version = LAMMPS_VERSION;
    plugin.style = "fix";
    plugin.name = styles[k].name;
    plugin.info = styles[k].info;
    plugin.author = "lammps-contact-dynamics project";
    plugin.creator.v2 = reinterpret_cast<lammpsplugin_factory2*>(styles[k].create);
    plugin.handle = handle;
    register_style(&plugin, lmp);
  }
}
