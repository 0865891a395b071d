// The subcommands of the `shaderlab` program. Each returns the process exit code:
// 0 success, 1 the work ran but something failed (a lab did not compile, a scene failed), 2 the
// command could not run (bad arguments, malformed lab.json, no GL context).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "shaderlab/batch/workers.h"
#include "shaderlab/render/isolated_render.h"

namespace shaderlab::cli {

struct CommonOptions {
    std::string backend = "auto";
    std::string labs_root;          // empty: defaultLabsRoot()
    std::vector<std::string> labs;  // --lab, repeatable; empty: every lab the labs root has
};

// The labs folder a command works on: --labs, else $SHADERLAB_LABS, else the course found from
// the current directory upward. Prints why and returns false when there is none.
bool resolveLabsRoot(const CommonOptions& common, std::string* labs_root);
// resolveLabsRoot, then lab `id` in it parsed into `out`; false, with the lab's errors printed,
// when there is no labs folder or the lab does not parse.
bool loadCommandLab(const CommonOptions& common, const std::string& id, std::string* labs_root,
                    LabSpecResult* out);
// Where students work: <course>/work, beside labs/.
std::string workRoot(const std::string& labs_root);

// The limits of each lab's render process (shaderlab/isolated_render.h, docs/grading.md "Limits").
struct LimitArgs {
    double timeout_s = 60.0;          // --timeout: drawing
    double compile_timeout_s = 30.0;  // --compile-timeout: context, files, compile and link
    std::size_t memory_mib = 2048;    // --memory: resident memory of the render process
};
IsolationLimits isolationLimits(const LimitArgs& args);

struct StartArgs {
    CommonOptions common;
    std::string lab;
    std::string into;  // empty: <course>/work
    bool force = false;
};
int runStart(const StartArgs& args);

struct RenderArgs {
    CommonOptions common;
    std::string submission;
    std::string out_dir;
    bool all_passes = false;
    std::string debug;  // --debug VIEW: each scene's vertex data instead (shaderlab/render/debug_view.h)
};
int runRender(const RenderArgs& args);

int runInfo(const std::string& backend);
// The backend --backend names ("auto" resolved: OSMesa where libOSMesa opens, else EGL); the first
// time "auto" falls back to EGL, says why on stderr in one line.
Backend chooseBackend(const std::string& name);

struct GradeArgs {
    CommonOptions common;
    std::string submission;
    std::string out_dir;
    std::string reference_root;        // empty: <labs>/../reference_solutions when it exists
    bool no_reference = false;         // grade against the stored goldens even when references exist
    std::vector<std::string> formats;  // json (always), gradescope, junit
    LimitArgs limits;
    std::string cache_dir;  // what is kept between runs (references, shaders); empty: out/.shaderlab
    bool no_cache = false;  // render the reference and compile every shader every time
};
int runGrade(const GradeArgs& args);

struct CheckArgs {
    CommonOptions common;
    std::string lab;
    std::string submission;  // empty: <course>/work (see `shaderlab start`)
    std::string out_dir;     // empty: out/check beside the labs folder
    bool no_reference = false;
    LimitArgs limits{10.0, 30.0, 2048};  // a short draw limit: a student waits on an endless loop
    std::string cache_dir;               // as GradeArgs
    bool no_cache = false;
};
int runCheck(const CheckArgs& args);

struct ViewArgs {
    CommonOptions common;
    std::string lab;
    std::string submission;      // empty: <course>/work, as `check`
    std::string reference_root;  // empty: reference_solutions beside labs/ when it has the lab
    bool no_reference = false;   // compare with the stored golden images
    double timeout_s = 5.0;      // one scene's render
    std::string scene;
    std::string image;         // pass.attachment shown first
    std::vector<float> orbit;  // yaw, pitch (degrees), zoom
    std::string mode = "student";
    int frames = 0;
    int exit_after_reloads = 0;
    std::string screenshot, screenshot_window;
    std::string panel_text;     // at exit: the panel's grade and verdict as text
    std::string debug = "off";  // first picture: the lab's, or a debug view of the vertex data
};
int runView(const ViewArgs& args);

// `shaderlab serve`: the browser workbench (framework/serve/).
struct ServeArgs {
    CommonOptions common;
    std::string lab;
    std::string submission;      // empty: <course>/work, as `check`
    std::string reference_root;  // empty: reference_solutions beside labs/ when it has the lab
    bool no_reference = false;
    std::string host = "127.0.0.1";
    int port = 8420;
    double timeout_s = 5.0;              // one scene's render for the picture
    LimitArgs limits{10.0, 30.0, 2048};  // the grade, as `check`
};
int runServe(const ServeArgs& args);

// `shaderlab watch`: runCheck() on every settled change of the lab's folder.
struct WatchArgs {
    CheckArgs check;
    int max_checks = 0;  // stop after this many checks (0: until interrupted)
};
int runWatch(const WatchArgs& args);

struct CompareArgs {
    std::string a, b;
    bool json = false;
    float tolerance = 0.05f;
};
int runCompare(const CompareArgs& args);

struct GoldensArgs {
    CommonOptions common;
    std::string reference_root;  // empty: <labs>/../reference_solutions
    std::string golden_root;     // empty: into each lab's folder; else <golden_root>/<lab>/golden/
    std::string corpus_root;     // empty: tests/corpus beside the labs folder
    bool no_hints = false;       // skip rendering the corpus mistakes into <lab>/hints/
};
int runGoldens(const GoldensArgs& args);

// For `goldens`: grades every mistake of each lab's corpus against the goldens under
// `stored_root` (empty: the labs' own) and writes the lab's known-mistake hints
// (shaderlab/mistake_hints.h) beside them. Returns error messages.
std::vector<std::string> writeHints(const std::string& labs_root, const std::string& corpus_root,
                                    const std::string& reference_root, const std::vector<std::string>& labs,
                                    const std::string& backend, const std::string& stored_root);

struct CorpusArgs {
    CommonOptions common;
    std::string corpus_root;     // empty: tests/corpus beside the labs folder
    std::string reference_root;  // empty: reference_solutions beside the labs folder
    std::string out_dir;
    bool use_reference = false;  // render the reference instead of reading the goldens
    double timeout_s = 10.0;
    bool margins = false;  // print and write how far each verdict is from turning (corpus_margins.h)
};
int runCorpus(const CorpusArgs& args);

// `shaderlab corpus add-case`: a case added to tests/corpus/<lab>/ from a folder of the lab's
// files, storing only those that differ from the reference (command_corpus_add_case.cpp).
struct CorpusAddCaseArgs {
    CommonOptions common;  // labs_root only
    std::string lab, name;
    std::string kind;                // mistake, alternative or broken
    std::vector<std::string> fails;  // a mistake's goals
    std::string status;              // a broken case's status (a mistake's is "failed")
    std::string about;
    std::string from;            // the lab's files, or a submission holding <lab>/
    std::string corpus_root;     // empty: tests/corpus beside the labs folder
    std::string reference_root;  // empty: reference_solutions beside the labs folder
};
int runCorpusAddCase(const CorpusAddCaseArgs& args);

// `shaderlab new-lab ID [--like LAB]`: a new lab's folders and files, which parse, render and
// pass `lab-check` but for the corpus (command_new_lab.cpp, docs/authoring.md).
struct NewLabArgs {
    CommonOptions common;  // labs_root only
    std::string id;
    std::string like;            // copy this lab's lab.json, files and README headings
    std::string title;           // empty: from the id ("12-normal-mapping": "Normal mapping")
    std::string reference_root;  // empty: reference_solutions beside the labs folder
    std::string corpus_root;     // empty: tests/corpus beside the labs folder
};
int runNewLab(const NewLabArgs& args);

// `shaderlab lab-check ID`: every check CI makes of one lab, one line each with its time
// (command_lab_check.cpp). `fix` rewrites the README's generated tables from lab.json.
struct LabCheckArgs {
    CommonOptions common;  // backend and labs_root
    std::string lab;
    std::string reference_root;  // empty: reference_solutions beside the labs folder
    std::string corpus_root;     // empty: tests/corpus beside the labs folder
    std::string out_dir;         // empty: out/lab-check/<lab> beside the labs folder
    double timeout_s = 10.0;     // one corpus case's render, as `corpus --timeout`
    bool fix = false;
};
int runLabCheck(const LabCheckArgs& args);

// `shaderlab mutants [--lab LAB]...`: coverage by mutation (command_mutants.cpp, docs/authoring.md
// "Mutants"): mutants of the reference solution graded as submissions; an undeclared survivor
// fails the run.
struct MutantsArgs {
    CommonOptions common;        // backend, labs_root and the labs (empty: every lab)
    std::string reference_root;  // empty: reference_solutions beside the labs folder
    std::string corpus_root;     // empty: tests/corpus beside the labs folder (equivalent_mutants)
    std::string out_dir;         // empty: out/mutants beside the labs folder
    double timeout_s = 10.0;     // one mutant's render
    int max_per_lab = 0;         // at most this many mutants per lab, spread evenly; 0: all
};
int runMutants(const MutantsArgs& args);

// `shaderlab scene-sweep LAB`: candidate variants of one of the lab's scenes, each judged by how
// well it separates each goal's corpus mistakes from its alternatives, ranked
// (command_scene_sweep.cpp, docs/authoring.md "Choosing scenes with scene-sweep").
struct SceneSweepArgs {
    CommonOptions common;  // backend and labs_root
    std::string lab;
    std::string scene;                  // the base scene (or the sweep file's "scene")
    std::vector<std::string> vary;      // PATH=VALUES, repeatable (scene_sweep.h has the grammar)
    std::string sweep_file;             // --sweep: scene, goals, vary and whole candidates in JSON
    std::vector<std::string> goals;     // judge under these ("all": every goal); empty: the base scene's
    std::vector<std::string> mistakes;  // the only mistakes of those goals a candidate must catch
    std::string out_dir;                // empty: out/scene-sweep/<lab> beside the labs folder
    std::string corpus_root;            // empty: tests/corpus beside the labs folder
    std::string reference_root;         // empty: reference_solutions beside the labs folder
    std::size_t max_candidates = 64;
    std::size_t top = 3;      // candidates printed as lab.json scenes
    double timeout_s = 10.0;  // one candidate's drawing, per corpus case
    bool keep = false;        // keep the swept lab, its goldens and the case folders (<out>/work)
};
int runSceneSweep(const SceneSweepArgs& args);

// `shaderlab batch`: every submission (folder or .zip) below `submissions_dir`, each lab in a
// worker process; see command_batch.cpp and docs/instructors.md.
struct BatchArgs {
    CommonOptions common;
    std::string submissions_dir;
    std::string out_dir;
    std::string reference_root;  // empty: reference_solutions beside labs/
    bool no_reference = false;
    std::string cache_dir;            // references and graded labs; empty: in <out>/.shaderlab
    int jobs = 0;                     // 0: the number of cores
    double timeout_s = 60.0;          // drawing (IsolationLimits::timeout_s)
    double compile_timeout_s = 30.0;  // context, files, compile and link
    std::string memory = "2G";  // resident memory of each render process; workers get 4G more address space
    std::string shard;          // "K/N": every N-th submission from the K-th; empty: all
    std::vector<std::string> formats;
    std::uint64_t max_unpacked_mib = 64;
};
int runBatch(const BatchArgs& args);

// The worker the batch starts for one unit of work (not for people: hidden from --help): its
// options are the task itself.
using BatchWorkerArgs = batch::WorkerTask;
int runBatchWorker(const BatchWorkerArgs& args);

// `shaderlab merge`: the summaries (and report folders) of several results folders in one.
struct MergeArgs {
    std::vector<std::string> inputs;
    std::string out_dir;
};
int runMerge(const MergeArgs& args);

// `shaderlab similarity`: who copied, per lab, across a class (framework/similarity/).
struct SimilarityArgs {
    CommonOptions common;                // labs_root and labs; the backend is not used
    std::string submissions_dir;         // SUBMISSIONS/<student>/<lab>/<files>, folders or zips
    std::string out_dir;                 // index.html, pairs.json, pairs/<lab>/<n>.html
    std::vector<std::string> earlier;    // earlier classes' submissions folders (candidates only)
    double threshold = 0.75;             // flag at this score or above (plus length_margin / sqrt(n))
    double length_margin = 0.5;          // how much more a short document must share (similarity.h)
    std::size_t min_shared = 10;         // and at least this many shared fingerprints
    int jobs = 0;                        // labs at once; 0: the number of cores
    std::size_t max_views = 200;         // side-by-side pages per lab
    std::size_t kgram = 12, window = 6;  // k and w of the winnowing (similarity.h says why)
};
int runSimilarity(const SimilarityArgs& args);

// `shaderlab class`: what the class did not learn, from a results folder (framework/classview/).
struct ClassArgs {
    std::string results_dir;  // of `batch` or `merge`
    std::string out_dir;      // index.html, class.json, pictures/
    std::string labs_root;    // for the known mistakes' pictures; empty: the course found from here
};
int runClass(const ClassArgs& args);

// `shaderlab gradescope-bundle`: the autograder zip of a Gradescope programming assignment.
struct GradescopeBundleArgs {
    CommonOptions common;
    std::string out_zip;
    std::string reference_root;          // empty: reference_solutions beside labs/
    std::string binary;                  // the shaderlab to pack; empty: this one, if portable
    std::string visibility = "visible";  // of the results: visible, hidden, after_due_date, after_published
    std::string tests = "goals";         // one Gradescope test per learning goal, or per scene ("scenes")
    double timeout_s = 60.0;
};
int runGradescopeBundle(const GradescopeBundleArgs& args);

// What the bundle's run_autograder runs: grades <root>/submission into <root>/results/results.json.
struct GradescopeRunArgs {
    CommonOptions common;
    std::string root = "/autograder";
    std::string reference_root;
    std::string visibility = "visible";
    std::string tests = "goals";
    double timeout_s = 60.0;
};
int runGradescopeRun(const GradescopeRunArgs& args);

}  // namespace shaderlab::cli
