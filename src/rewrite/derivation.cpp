// A derivation step in full: cut branches, rewrite with the step's table, decompose,
// then let query modules and the environment see the new string.
#include "graftal/rewrite/derivation.hpp"

#include <cmath>

#include "graftal/core/cpfg_random.hpp"
#include "graftal/core/parallel.hpp"
#include "graftal/core/random_stream.hpp"
#include "output_files.hpp"
#include "rewriting_engine.hpp"

namespace graftal {

namespace {

// Whether `s` has a module with a symbol in [a, b].
bool containsSymbol(const ModuleString& s, Symbol a, Symbol b) {
    for (Symbol x : s.symbols())
        if (x >= a && x <= b) return true;
    return false;
}

bool usesQueries(const LSystem& ls) {
    auto isQuery = [](Symbol s) { return s >= kQueryE && s <= kQueryU; };
    for (Symbol s : ls.axiom.symbols())
        if (isQuery(s)) return true;
    for (const auto* list : {&ls.productions, &ls.decomposition})
        for (const auto& p : *list)
            for (const auto& m : p.successor)
                if (isQuery(m.symbol)) return true;
    return false;
}

// Recursive rewriting (decomposition, homomorphism) done level by level: only modules
// produced at the previous level are rewritten again, which for context-free productions
// is the same as expanding each module recursively.
void rewriteRecursively(RewritingEngine& engine, ModuleString& s, int depth, int stepNumber,
                        std::size_t limit) {
    ModuleString next;
    std::vector<std::uint8_t> active, produced;
    for (int level = 0; level < depth; ++level) {
        bool any =
            engine.step(s, next, stepNumber, 0, limit, level == 0 ? nullptr : &active, &produced);
        if (!any) break;
        std::swap(s, next);
        std::swap(active, produced);
    }
}

}  // namespace

Derivation::Derivation(LSystem lsystem, DerivationOptions options)
    : lsystem_(std::move(lsystem)),
      options_(options),
      current_(std::make_unique<ModuleString>(lsystem_.axiom)),
      next_(std::make_unique<ModuleString>(options.precision)) {
    current_->setPrecision(options.precision);
    std::uint64_t seed = options.seed.value_or(lsystem_.seed);
    unsigned threads = options.threads ? options.threads : defaultThreadCount();
    rules_ = std::make_unique<RewritingEngine>(lsystem_, lsystem_.productions, seed, threads);
    if (!lsystem_.decomposition.empty())
        decomposition_ =
            std::make_unique<RewritingEngine>(lsystem_, lsystem_.decomposition, seed, threads);
    // Q and Z, then the variables, all 0 until Start: runs.
    state_.assign(lsystem_.stateNames.size(), 0.0);
    state_[1] = lsystem_.derivationLength;
    for (const auto& [slot, value] : lsystem_.initialState) state_[slot] = value;
    files_ = std::make_unique<ModelOutputFiles>(std::filesystem::path(lsystem_.file).parent_path());
    rules_->setState(state_.data(), &options_.print, files_.get());
    if (decomposition_) decomposition_->setState(state_.data(), &options_.print, files_.get());
    const bool cpfgStreams = options_.random.value_or(lsystem_.random) == RandomStreams::Cpfg;
    if (cpfgStreams) deferQueries_ = lsystem_.cpfgViewBox;
    // A model that never draws (and cuts no branch, which cpfg does as the step reaches
    // the cut) gives the same string either way: it keeps the parallel rewriting and the
    // counted last step, which cpfg's order would rule out.
    if (cpfgStreams && (lsystem_.drawsRandomNumbers() || lsystem_.usesCut())) {
        // cpfg's generators, drawn in cpfg's order: every step in string order. Only the
        // productions draw to choose (decomposition takes the first applicable one).
        // cpfg's batch run (`cpfg -g -str`, the string it saves) leaves the productions'
        // state where the C library starts it, whatever `seed:` says; its interactive run
        // seeds it with seed48 from `seed:`, which a seed given to the derivation stands for.
        cpfgRandom_ = std::make_unique<CpfgRandom>(
            options_.seed ? static_cast<long>(*options_.seed & 0xFFFFFFFF) : 0);
        rules_->useCpfgRandom(cpfgRandom_.get(), lsystem_.hasSeedLine || options_.seed, true);
        if (decomposition_) decomposition_->useCpfgRandom(cpfgRandom_.get(), false);
    }
    if (!lsystem_.startBlock.empty()) rules_->runBlock(lsystem_.startBlock, nullptr, 0, 0);
    if (!lsystem_.axiomArguments.empty()) {
        // Axiom parameters that read variables see what Start: left in them.
        const auto& starts = current_->paramStarts();
        for (const auto& a : lsystem_.axiomArguments) {
            EvalContext ctx;
            ctx.state = state_.data();
            ctx.print = &options_.print;
            ctx.files = files_.get();
            ctx.functions = &lsystem_.functions;
            ctx.userFunctions = lsystem_.userFunctions.get();
            ctx.curves = &lsystem_.curves;
            ctx.cpfgRandom = cpfgRandom_.get();
            std::uint64_t draw = 0;
            ctx.uniform = [&] { return uniformAt(seed, 0, a.module, (a.param << 20) + draw++); };
            current_->setParam(starts[a.module] + a.param, a.value.evaluate({}, &ctx));
        }
    }
    if (rules_->parametric() && !current_->hasParameters()) {
        // Parametric strings always carry offsets, so every module reads the same way.
        current_->rawParamStart().assign(current_->size() + 1, 0);
    }
    queries_ = usesQueries(lsystem_);
    environment_ = options.environment;
    if (!environment_) {
        ownedEnvironment_ = makeEnvironment(lsystem_);
        environment_ = ownedEnvironment_.get();
    }
    // cpfg decomposes what each step produces, never the axiom as written; the queries of
    // the axiom are answered all the same.
    answerQueries(0);
}

Derivation::~Derivation() = default;

// '%' removes itself and the rest of its branch: everything up to the ']' that closes the
// branch it stands in (or the end of the string on the main axis).
static bool pruneCuts(const ModuleString& s, ModuleString& out) {
    if (!containsSymbol(s, '%', '%')) return false;
    out = ModuleString(s.precision());
    out.reserve(s.size(), s.paramCount());
    if (s.hasParameters()) out.rawParamStart().assign(1, 0);
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s.symbol(i) == '%') {
            int depth = 0;
            for (++i; i < s.size(); ++i) {
                Symbol c = s.symbol(i);
                if (c == '[')
                    ++depth;
                else if (c == ']' && depth-- == 0)
                    break;
            }
            if (i >= s.size()) break;
        }
        out.push(s.symbol(i), s.params(i));
    }
    return true;
}

void Derivation::decompose(int stepNumber) {
    if (!decomposition_) return;
    rewriteRecursively(*decomposition_, *current_, lsystem_.decompositionDepth, stepNumber,
                       options_.memoryLimit);
}

void Derivation::answerQueries(int stepNumber) {
    if (!queries_) return;
    ModuleString& s = *current_;
    if (!containsSymbol(s, kQueryE, kQueryU)) return;
    // The turtle sees the string after the homomorphism; query modules keep their order.
    ModuleString seen =
        lsystem_.homomorphism.empty() ? ModuleString{} : applyHomomorphism(lsystem_, s, options_);
    const ModuleString& walked = lsystem_.homomorphism.empty() ? s : seen;
    std::vector<bool> wanted(lsystem_.symbols.size(), false);
    for (Symbol q = kQueryE; q <= kQueryU; ++q) wanted[q] = true;
    if (!options_.queryResolver)
        throw Error(SourceLocation{lsystem_.file, 0, 0},
                    "the query modules (?E ?P ?H ?L ?U) of step " + std::to_string(stepNumber) +
                        " need the turtle, and the derivation was given none "
                        "(DerivationOptions::queryResolver)");
    std::vector<TurtleFrame> frames;
    options_.queryResolver(lsystem_, walked, wanted,
                           [&](std::size_t, const TurtleFrame& f) { frames.push_back(f); });

    std::vector<std::size_t> positions;
    for (std::size_t i = 0; i < s.size(); ++i)
        if (s.symbol(i) >= kQueryE && s.symbol(i) <= kQueryU) positions.push_back(i);
    if (positions.size() != frames.size())
        throw Error(SourceLocation{lsystem_.file, 0, 0},
                    "the homomorphism changes the number of query modules (?E ?P ?H ?L ?U) "
                    "in step " +
                        std::to_string(stepNumber) + "; they must map to themselves");

    const auto& starts = s.paramStarts();
    std::vector<CommunicationRequest> requests;
    // The environment answers in doubles; strings of floats get the answers rounded after.
    std::vector<std::vector<double>> answers(positions.size());
    for (std::size_t k = 0; k < positions.size(); ++k) {
        std::size_t i = positions[k];
        const TurtleFrame& f = frames[k];
        std::span<double> p;
        if (!starts.empty()) {
            answers[k].assign(s.params(i).begin(), s.params(i).end());
            p = answers[k];
        }
        const Vec3* v = nullptr;
        const Vec3 cpfgUp = f.up * -1.0;  // cpfg's up vector is -U (its L = H x U)
        switch (s.symbol(i)) {
            case kQueryP:
                v = &f.position;
                break;
            case kQueryH:
                v = &f.heading;
                break;
            case kQueryL:
                v = &f.left;
                break;
            case kQueryU:
                v = &cpfgUp;
                break;
            default:
                requests.push_back({i, f, p});
                continue;
        }
        // Rotations leave 1e-17-sized noise where a component is 0; snap it so that
        // derived strings print the 0 a user expects.
        auto snap = [](double x) { return std::fabs(x) < 1e-12 ? 0.0 : x; };
        double xyz[3] = {snap(v->x), snap(v->y), snap(v->z)};
        for (std::size_t c = 0; c < p.size() && c < 3; ++c) p[c] = xyz[c];
    }
    if (!requests.empty() && environment_) environment_->respond(stepNumber, requests);
    for (std::size_t k = 0; k < positions.size(); ++k)
        for (std::size_t c = 0; c < answers[k].size(); ++c)
            s.setParam(starts[positions[k]] + c, answers[k][c]);
}

void Derivation::afterStep(int stepNumber) {
    decompose(stepNumber);
    if (deferQueries_ && queries_)
        pendingQueries_ = stepNumber;
    else
        answerQueries(stepNumber);
}

void Derivation::step() {
    options_.cancel.check();
    if (pendingQueries_ >= 0) {
        answerQueries(pendingQueries_);
        pendingQueries_ = -1;
    }
    int stepNumber = steps_ + 1;
    // Cut first, into a scratch string, so that a step that fails leaves current_ intact.
    ModuleString pruned;
    ModuleString& source =
        lsystem_.usesCut() && !cpfgRandom_ && pruneCuts(*current_, pruned) ? pruned : *current_;
    state_[0] = stepNumber;
    if (!lsystem_.startEachBlock.empty())
        rules_->runBlock(lsystem_.startEachBlock, nullptr, stepNumber, 0);
    // The string before the step is not kept once the step succeeds.
    rules_->stepConsuming(source, *next_, stepNumber, lsystem_.tableForStep(stepNumber),
                          options_.memoryLimit);
    options_.cancel.check();
    std::swap(current_, next_);
    ++steps_;
    afterStep(stepNumber);
    if (!lsystem_.endEachBlock.empty())
        rules_->runBlock(lsystem_.endEachBlock, nullptr, stepNumber, 1);
    if (options_.progress) options_.progress(stepNumber, current_->size());
}

std::vector<std::uint64_t> Derivation::countNextStep() {
    // What happens after the rewriting (decomposition, answers to queries, End each
    // blocks) could change the string, and blocks run per module: those steps are done.
    if (decomposition_ || queries_ || cpfgRandom_ || !lsystem_.startEachBlock.empty() ||
        !lsystem_.endEachBlock.empty() || !lsystem_.endBlock.empty() || lsystem_.usesCut())
        return {};
    options_.cancel.check();
    const int stepNumber = steps_ + 1;
    const double q = state_[0];
    state_[0] = stepNumber;  // conditions may read the step number
    std::vector<std::uint64_t> counts;
    try {
        rules_->countStep(*current_, counts, stepNumber, lsystem_.tableForStep(stepNumber),
                          options_.memoryLimit);
    } catch (...) {
        state_[0] = q;
        throw;
    }
    state_[0] = q;
    return counts;
}

void Derivation::run(int steps) {
    for (int i = 0; i < steps; ++i) step();
}

void Derivation::finish() {
    if (finished_ || steps_ == 0) return;
    finished_ = true;
    if (!lsystem_.endBlock.empty()) rules_->runBlock(lsystem_.endBlock, nullptr, steps_ + 1, 0);
}

namespace {}  // namespace

Derivation::Derivation(const Model& model, DerivationOptions options)
    : Derivation(model.lsystem, std::move(options)) {}

ModuleString derive(const Model& model, int steps, DerivationOptions options) {
    return derive(model.lsystem, steps, std::move(options));
}

ModuleString derive(const LSystem& lsystem, int steps, DerivationOptions options) {
    Derivation d(lsystem, options);
    d.run(steps < 0 ? lsystem.derivationLength : steps);
    d.finish();
    return d.take();
}

ModuleString applyHomomorphism(const LSystem& lsystem, const ModuleString& modules,
                               DerivationOptions options) {
    ModuleString s = modules;
    if (lsystem.homomorphism.empty()) return s;
    RewritingEngine engine(lsystem, lsystem.homomorphism, options.seed.value_or(lsystem.seed),
                           options.threads ? options.threads : defaultThreadCount());
    // The homomorphism sees the variables as they start (it runs outside the derivation).
    std::vector<double> state(lsystem.stateNames.size(), 0.0);
    state[1] = lsystem.derivationLength;
    for (const auto& [slot, value] : lsystem.initialState) state[slot] = value;
    engine.setState(state.data(), &options.print);
    rewriteRecursively(engine, s, lsystem.homomorphismDepth, 0, options.memoryLimit);
    return s;
}

}  // namespace graftal
