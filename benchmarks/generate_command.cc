#include "generate_command.h"

#include <iostream>

#include "exit_codes.h"
#include "input_error.h"
#include "tow_generator.h"

namespace fibrecheck {

void add_generate_command(CLI::App& app, int& exit_code) {
  CLI::App* generate = app.add_subcommand("generate", "Generate scenes");
  generate->require_subcommand(1);
  auto o = std::make_shared<TowOptions>();
  auto out = std::make_shared<std::string>();
  CLI::App* tow = generate->add_subcommand(
      "tow", "A random tow of nearly parallel fibres, placed without overlap, then compacted");
  tow->add_option("--fibres", o->fibres, "Number of fibres")->capture_default_str();
  tow->add_option("--slices", o->slices, "Cross-sections n")->capture_default_str();
  tow->add_option("--seed", o->seed, "Random seed (same seed, same tow)")->capture_default_str();
  tow->add_option("--volume-fraction", o->volume_fraction,
                  "Fibre volume fraction before compaction")
      ->capture_default_str();
  tow->add_option("--misalignment", o->misalignment_deg, "Largest misalignment angle, degrees")
      ->capture_default_str();
  tow->add_option("--length", o->length, "Fibre length, mm")->capture_default_str();
  tow->add_option("--radius", o->radius, "Fibre radius, mm")->capture_default_str();
  tow->add_option("--youngs-modulus", o->youngs_modulus, "Young's modulus, MPa")
      ->capture_default_str();
  tow->add_option("--compaction", o->compaction, "Cross-section scale factor F in (0, 1]")
      ->capture_default_str();
  tow->add_option("--out", *out, "Scene file to write")->required();
  tow->callback([o, out, &exit_code] {
    try {
      const Scene scene = generate_tow(*o);
      write_scene(*out, scene);
      std::cout << "wrote " << *out << ": " << scene.fibres.size() << " fibres, "
                << scene.contact.slices << " slices, compaction " << o->compaction << "\n";
      exit_code = kExitConverged;
    } catch (const InputError& e) {
      std::cerr << "fibrecheck generate tow: error: " << e.what() << "\n";
      exit_code = kExitBadInput;
    } catch (const std::exception& e) {
      std::cerr << "fibrecheck generate tow: error: " << e.what() << "\n";
      exit_code = kExitBadInput;
    }
  });
}

}  // namespace fibrecheck
