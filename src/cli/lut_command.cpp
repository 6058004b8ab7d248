// bssrdf lut: lookup tables for renderers (radial, albedo-radius, transmission, pre-integrated,
// penumbra, separable kernel, Gaussian mixture) as OpenEXR, JSON, CSV or shader arrays; --all for the
// whole materials database, one file per material. The kinds are in lut_kinds.cpp, built by the library.
#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>

#include "bssrdf/error.hpp"
#include "bssrdf/io/atomic_file.hpp"
#include "bssrdf/io/exr_table.hpp"
#include "bssrdf/parallel.hpp"
#include "commands.hpp"
#include "lut_kinds.hpp"

namespace bssrdf::cli {
namespace {

std::string encode(const BuiltTable& built, const std::string& format, bool half) {
  const auto other = built.other_formats.find(format);
  if (other != built.other_formats.end()) return with_flag_names({{"format", "--format"}}, other->second);
  if (format == "exr") return encode_exr(built.table, half ? ExrPixelType::half : ExrPixelType::float32);
  if (format == "json") return to_json(built.table);
  if (format == "csv") return to_csv(built.table);
  if (format == "glsl" || format == "hlsl")
    throw InvalidInput("--format", "'" + format + "'",
                       "exr, json or csv for --kind " + built.table.kind + " (glsl and hlsl: --kind separable)");
  throw InvalidInput("--format", "'" + format + "'", "exr, json, csv, or glsl/hlsl for --kind separable");
}

std::string format_for(const LutOptions& o, const std::string& path) {
  if (!o.format.empty()) return o.format;
  const auto ext = std::filesystem::path(path).extension().string();
  if (ext == ".exr") return "exr";
  if (ext == ".json") return "json";
  if (ext == ".csv") return "csv";
  if (ext == ".glsl") return "glsl";
  if (ext == ".hlsl") return "hlsl";
  throw InvalidInput("-o", "'" + path + "'", "a file ending in .exr, .json, .csv, .glsl or .hlsl (or give --format)");
}

// A material's name as a file-name stem: lower case, anything but letters and digits as '-'.
std::string file_stem(const std::string& material) {
  std::string name;
  for (char ch : material)
    name += std::isalnum(static_cast<unsigned char>(ch)) ? static_cast<char>(std::tolower(ch)) : '-';
  return name;
}

std::string file_name(const std::string& material, const std::string& kind, const std::string& format) {
  return file_stem(material) + "-" + kind + "." + format;
}

// Every material of the database (--all), one file each in --output-dir: built in parallel (--threads
// workers, each table single-threaded) and written in database order as soon as every earlier material is
// done, by whichever worker finds the next one ready, so files and messages do not depend on the thread
// count, writing overlaps building and each encoded table is freed once written (its memory then serves
// the next: fresh pages cost a page fault each). A material this kind cannot tabulate (e.g. a channel
// that does not scatter) is skipped with its reason, one line each on stderr; the others are still written.
void tabulate_all(const LutOptions& o, const TableKind& kind) {
  if (!o.medium.material.empty() || !o.medium.sigma_a.empty())
    throw InvalidInput("--all: give no --material or coefficients with --all");
  const std::string format = o.format.empty() ? "exr" : o.format;
  // With --all, -o names the directory (one file per material in it), never one file.
  if (!o.output.empty() && !o.output_dir.empty())
    throw InvalidInput("-o: with --all, -o is the directory (the same as --output-dir); give one of them");
  if (!o.output.empty() && std::filesystem::path(o.output).has_extension())
    throw InvalidInput("-o", "'" + o.output + "'",
                       "a directory with --all (one file per material is written in it; choose their format with -f)");
  const std::filesystem::path dir = !o.output.empty() ? o.output : o.output_dir.empty() ? "." : o.output_dir;
  if (!std::filesystem::is_directory(dir))
    throw InvalidInput(o.output.empty() ? "--output-dir" : "-o", "'" + dir.string() + "'", "an existing directory");
  // With --preview NAME.png each material also gets <material>-NAME.png beside its table.
  if (!o.preview.empty() && std::filesystem::path(o.preview).extension() != ".png")
    throw InvalidInput("--preview", "'" + o.preview + "'",
                       "a file name ending in .png (with --all: <material>-NAME.png each)");
  // With --db, every material of that database (without it, the bundled ones). Each is then looked
  // up as every command looks up a name, in the bundled database plus --db: a name clash between
  // the two is one error here, before any work, not one skipped table per material.
  const auto lookup = MaterialDatabase::load_with_user(o.medium.db);  // every material's, loaded once
  const auto database =
      MaterialDatabase::load(o.medium.db.empty() ? default_materials_dir() : std::filesystem::path(o.medium.db));
  const auto& materials = database.all();
  const auto progress = progress_bar("lut --all");
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> encoded(materials.size()), failure(materials.size()), previews(materials.size()),
      notes(materials.size());
  std::vector<char> ready(materials.size(), 0);
  std::size_t done = 0, next_to_write = 0, written = 0;
  bool writing = false, stopped = false;  // a worker is writing (the others go on building); a write failed
  std::vector<std::string> skipped;
  std::mutex mutex;  // guards ready, done, next_to_write, writing, stopped and the progress bar
  const auto write_one = [&](std::size_t i) {  // outside the lock; only the one writer calls it
    if (!failure[i].empty()) {
      skipped.push_back(materials[i].name + ": " + failure[i]);
      return;
    }
    const auto path = dir / file_name(materials[i].name, o.kind, format);
    write_file_atomically(path, encoded[i]);  // an unwritable directory stops the batch
    std::string().swap(encoded[i]);
    ++written;
    if (!o.quiet && !progress) std::cout << "written: " << path.string() << '\n';
    if (previews[i].empty()) return;
    const auto png = dir / (file_stem(materials[i].name) + "-" + std::filesystem::path(o.preview).filename().string());
    write_file_atomically(png, previews[i]);
    std::string().swap(previews[i]);
    if (!o.quiet && !progress) std::cout << "written: " << png.string() << '\n';
  };
  parallel_for(materials.size(), o.threads, [&](std::size_t i) {
    LutOptions one = o;
    one.medium.material = materials[i].name;
    one.medium.loaded = &lookup;
    one.threads = 1;
    try {
      encoded[i] = encode(kind.build(one), format, o.half);
      if (!o.preview.empty()) {
        auto preview = render_preview(one, one.medium.resolve());
        previews[i] = std::move(preview.png);
        if (!preview.warning.empty()) notes[i] = materials[i].name + ": " + preview.warning;
      }
    } catch (const InvalidInput& e) {
      failure[i] = e.what();
    }
    std::unique_lock lock(mutex);
    ready[i] = 1;
    if (progress) progress(++done, materials.size());
    if (writing || stopped) return;  // the writer will reach this one; after a failed write, nothing more
    writing = true;
    while (next_to_write < materials.size() && ready[next_to_write]) {
      const std::size_t k = next_to_write++;
      lock.unlock();
      try {
        write_one(k);
      } catch (...) {
        lock.lock();
        stopped = true;
        throw;
      }
      lock.lock();
    }
    writing = false;
  });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (const auto& line : skipped) std::cerr << "bssrdf: skipped " << line << '\n';
  for (std::size_t i = 0; i < materials.size(); ++i)
    if (!notes[i].empty() && failure[i].empty()) std::cerr << "bssrdf: " << notes[i] << '\n';
  if (!o.quiet)
    std::cout << written << " " << o.kind << " tables in " << format_number(std::round(seconds * 1000) / 1000) << " s"
              << (skipped.empty() ? "" : ", " + std::to_string(skipped.size()) + " materials skipped (see stderr)")
              << "\n";
}

// "[value]" of a library default, for the help texts.
std::string default_of(double value) { return " [" + format_number(value) + "]"; }

}  // namespace

Action register_lut(CLI::App& app) {
  auto o = std::make_shared<LutOptions>();
  auto* sub =
      app.add_subcommand("lut", "Lookup tables for renderers: OpenEXR, JSON or CSV with their conventions recorded");
  o->medium.add_to(*sub);
  o->colour.add_to(*sub);
  std::string kinds_help = "Table:";
  for (const auto& kind : table_kinds())
    kinds_help += "\n  " + std::string(kind.name) + ": " + std::string(kind.summary);
  sub->add_option("--kind,-k", o->kind, kinds_help + "\n[radial]");
  sub->add_option(
      "--layout", o->layout,
      "albedo-radius: pbrt (100 x 64, pbrt's spacing), family (--size) or adaptive (--table-tolerance) [pbrt]");
  sub->add_option("--table-tolerance", o->table_tolerance,
                  "albedo-radius --layout adaptive: interpolation error allowed, relative to each row's peak" +
                      default_of(kAdaptiveTableTolerance) +
                      "; cost grows as 1/tolerance (each axis refined up to 2048 points; minutes at 1e-3, progress "
                      "shown on a terminal)");
  sub->add_option("--size", o->size,
                  "albedo-radius with --layout family: ALBEDOSxRADII, e.g. 64x48; preintegrated: N.LxCURVATURES; "
                  "penumbra: SHADOWSxWIDTHS [256x256]");
  auto* model_option =
      sub->add_option("--model", o->model,
                      "Profile model (see 'bssrdf models'), or auto: the cheapest measured within "
                      "--accuracy of Monte Carlo here [the registry's default: exact inside its domain, else "
                      "the most accurate model measured there]");
  sub->add_option("--accuracy", o->accuracy,
                  "With --model auto: relative error allowed in the total and in R(r) (L2) [0.1]");
  sub->add_option("--tolerance", o->tolerance,
                  "radial: relative interpolation error bound" + default_of(RadialTableOptions{}.tolerance) +
                      "; albedo-radius: beam-integral quadrature tolerance" +
                      default_of(AlbedoRadiusOptions{}.tolerance) +
                      "; with --pixel (radial, separable, preintegrated, gaussians): the largest image error, 8-bit "
                      "sRGB code values, "
                      "that sizes the table (--taps/--range, --size, --count override)");
  sub->add_option(
      "--pixel", o->pixel,
      "radial, separable, preintegrated, gaussians: pixel size in --unit; the table records how wrong it looks there "
      "(bssrdf:image_error, code values against the model it tabulates)");
  sub->add_option(
      "--energy", o->energy,
      "Fraction of each channel's total inside the checked radius range" + default_of(RadialTableOptions{}.energy));
  sub->add_option("--interpolation", o->interpolation,
                  "How the consumer interpolates: catmull-rom or linear [" +
                      std::string(to_string(RadialTableOptions{}.interpolation)) + "]");
  sub->add_option("-o,--output", o->output,
                  "Output file: .exr, .json, .csv (.glsl, .hlsl for separable); with --all: the directory")
      ->check(file_name("-o"));
  sub->add_option("--format,-f", o->format, "exr, json, csv; glsl or hlsl for separable [from the file's extension]");
  sub->add_flag("--half", o->half, "OpenEXR: half-float channels instead of float32");
  sub->add_flag("--all", o->all, "Every material of the database, one file per material in --output-dir");
  sub->add_option("--output-dir", o->output_dir, "Directory for --all [.]")->check(file_name("--output-dir"));
  add_count_option(*sub, "--threads", o->threads, 0, kMaxThreads, "Threads (0: all) [1]; results never depend on it");
  sub->add_flag("-q,--quiet", o->quiet, "Print nothing on stdout");
  sub->add_option("--thickness", o->thickness, "transmission: slab thicknesses in --unit, comma-separated");
  sub->add_option("--d-min", o->d_min,
                  "transmission: smallest thickness [0.1 of the shortest transport mfp over the channels; --model "
                  "multipole alone: 2 of the longest]");
  sub->add_option("--d-max", o->d_max,
                  "transmission: largest thickness [40 of the longest transport mfp over the channels]");
  add_count_option(
      *sub, "--samples", o->samples, 2, kMaxThicknessSamples,
      "transmission: thicknesses, log-spaced from --d-min to --d-max [" + std::to_string(kThicknessSamples) + "]");
  sub->add_flag("--reference", o->reference,
                "radial: tabulate the Monte Carlo reference instead of a model (bins with standard errors; --photons, "
                "default 1e6); "
                "transmission: Monte Carlo where the multipole is invalid (else omitted)");
  sub->add_option("--layers", o->layers,
                  "radial --reference: a layer stack file (bssrdf-layers JSON, as for 'bssrdf reference --layers')");
  sub->add_flag("--reference-everywhere", o->reference_everywhere,
                "transmission: Monte Carlo reference at every thickness");
  auto* photons_option =
      add_count_option(*sub, "--photons", o->photons, 1, kMaxPhotons,
                       "Monte Carlo photons per channel: per thickness for transmission [" +
                           std::to_string(TransmissionTableOptions{}.photons) + "], for radial --reference [" +
                           std::to_string(ReferenceRadialOptions{}.photons) + "]");
  add_count_option(*sub, "--seed", o->seed, 0, kMaxSeed,
                   "Monte Carlo seed (transmission --reference, radial --reference) [1]");
  sub->add_option(
         "--preview", o->preview,
         "Also (or, without -o, only) write a PNG preview of the material: shadow-edge swatch + colour falloff")
      ->check(file_name("--preview"));
  add_count_option(*sub, "--taps", o->taps, 3, 255,
                   "separable: number of taps, odd, >= 3 (Jimenez: 11, 17, 25) [" +
                       std::to_string(SeparableKernelOptions{}.taps) + "]");
  sub->add_option("--range", o->range,
                  "separable: kernel half-width in --unit, or jimenez (3 mm if taps > 20 else 2 mm) [the band holding "
                  "--band of the widest channel's light]");
  sub->add_option("--band", o->band,
                  "separable: fraction of the widest channel's light inside +-range when --range is not given" +
                      default_of(SeparableKernelOptions{}.band));
  add_count_option(*sub, "--count,-n", o->count, 1, 32,
                   "gaussians: number of shared-variance Gaussians fitted [6; with --model quantized and no --count: "
                   "its own mixture]");
  sub->add_option("--curvature-max", o->curvature_max,
                  "preintegrated: largest curvature 1/r, in 1/--unit [1/r_50 of the widest channel]");
  sub->add_option("--width-max", o->width_max, "penumbra: widest penumbra, in --unit [8 r_50 of the widest channel]");

  return [o, model_option, photons_option, sub] {
    o->model_given = model_option->count() > 0;
    o->taps_given = sub->count("--taps") > 0;
    o->range_given = sub->count("--range") > 0;
    o->size_given = sub->count("--size") > 0;
    o->count_given = sub->count("--count") > 0;
    o->photons_given = photons_option->count() > 0;
    if (!o->layers.empty() && (o->kind != "radial" || !o->reference))
      throw InvalidInput("--layers: only with --kind radial --reference (Monte Carlo)");
    const auto& kind = table_kind(o->kind);
    if (o->all) return tabulate_all(*o, kind);
    if (o->output.empty() && o->preview.empty())
      throw InvalidInput("-o: give an output file (.exr, .json, .csv), or --preview FILE.png");
    // Everything is made before anything is written: an error leaves no file, not even the preview.
    std::optional<RenderedPreview> preview;
    if (!o->preview.empty()) preview = render_preview(*o, o->medium.resolve());
    std::optional<BuiltTable> built;
    double ms = 0;
    if (!o->output.empty()) {
      const std::string format = format_for(*o, o->output);
      const auto start = std::chrono::steady_clock::now();
      built = kind.build(*o);
      ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      write_file_atomically(o->output, encode(*built, format, o->half));
    }
    if (preview) {
      write_file_atomically(o->preview, preview->png);
      if (!preview->warning.empty()) std::cerr << "bssrdf: " << preview->warning << '\n';
      if (!o->quiet) std::cout << "preview: " << o->preview << " (" << preview->description << ")\n";
    }
    if (built && !o->quiet)
      std::cout << built->summary << "built in " << format_number(std::round(ms * 100) / 100)
                << " ms\nwritten: " << o->output << '\n';
  };
}

}  // namespace bssrdf::cli
