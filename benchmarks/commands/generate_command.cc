#include "generate_command.h"

#include <iostream>
#include <map>

#include "exit_codes.h"
#include "input_error.h"

namespace fibrecheck {

namespace {
/// The command-line option of each TowOptions field.
const std::map<std::string, std::string> kOptionOfField = {{"fibres", "--fibres"},
                                                           {"slices", "--slices"},
                                                           {"seed", "--seed"},
                                                           {"volume_fraction", "--volume-fraction"},
                                                           {"misalignment_deg", "--misalignment"},
                                                           {"length", "--length"},
                                                           {"radius", "--radius"},
                                                           {"youngs_modulus", "--youngs-modulus"},
                                                           {"compaction", "--compaction"},
                                                           {"steps", "--steps"}};
}  // namespace

int run_generate(const GenerateArguments& args) {
  Scene scene;
  try {
    scene = generate_tow(args.tow);
  } catch (const InputError& e) {
    const auto option = kOptionOfField.find(e.field());
    throw InputError("command line", option == kOptionOfField.end() ? e.field() : option->second,
                     e.reason());
  }
  write_scene(args.out, scene);
  std::cout << "wrote " << args.out << ": " << scene.fibres.size() << " fibres, "
            << scene.contact.slices << " slices, compaction " << args.tow.compaction;
  if (!scene.steps.empty()) std::cout << " in " << scene.steps.size() << " steps";
  std::cout << "\n";
  return kExitConverged;
}

CLI::App* add_generate_command(CLI::App& app, GenerateArguments& args) {
  CLI::App* generate = app.add_subcommand("generate", "Generate scenes");
  generate->require_subcommand(1);
  TowOptions& o = args.tow;
  CLI::App* tow = generate->add_subcommand(
      "tow", "A random tow of nearly parallel fibres, placed without overlap, then compacted");
  tow->add_option("--fibres", o.fibres, "Number of fibres")->capture_default_str();
  tow->add_option("--slices", o.slices, "Cross-sections n")->capture_default_str();
  tow->add_option("--seed", o.seed, "Random seed (same seed, same tow)")->capture_default_str();
  tow->add_option("--volume-fraction", o.volume_fraction, "Fibre volume fraction before compaction")
      ->capture_default_str();
  tow->add_option("--misalignment", o.misalignment_deg, "Largest misalignment angle, degrees")
      ->capture_default_str();
  tow->add_option("--length", o.length, "Fibre length, mm")->capture_default_str();
  tow->add_option("--radius", o.radius, "Fibre radius, mm")->capture_default_str();
  tow->add_option("--youngs-modulus", o.youngs_modulus, "Young's modulus, MPa")
      ->capture_default_str();
  tow->add_option("--compaction,--final-compaction", o.compaction,
                  "Cross-section scale factor F in (0, 1] (with --steps: the last step's)")
      ->capture_default_str();
  tow->add_option("--steps", o.steps,
                  "Write the tow uncompacted with a load path of K compaction steps down to F "
                  "(0: the tow as compacted)")
      ->capture_default_str();
  tow->add_option("--first-compaction", o.first_compaction,
                  "With --steps: the first step's factor (the steps run evenly from it to F; "
                  "default: evenly from the uncompacted tow)");
  tow->add_option("--friction", o.friction, "Coulomb coefficient mu of the contacts")
      ->capture_default_str();
  tow->add_option("--out", args.out, "Scene file to write")->required();
  return tow;
}

}  // namespace fibrecheck
