# The two commands of the README: `make demo` and `make test`. Each installs the Debian
# packages that are missing, configures, builds, and then renders the gallery or runs
# every test. `make fuzz` builds the fuzz targets with clang, libFuzzer and the sanitizers
# in their own folder and runs each for FUZZ_SECONDS (docs/reliability.md).

BUILD_DIR ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
DEBIAN_PACKAGES := cmake g++ make pkg-config ccache libgtest-dev libcli11-dev libcairo2-dev libpng-dev \
                   nlohmann-json3-dev poppler-utils libembree-dev libtinygltf-dev
# Fractal music: MIDI files (libsmf), audio (FluidSynth and a General MIDI SoundFont),
# engraved scores (LilyPond).
MUSIC_PACKAGES := libsmf-dev libfluidsynth-dev timgm6mb-soundfont lilypond
# graftal animate: GIF, animated WebP and MP4 (H.264 through libx264) encoders.
ANIMATION_PACKAGES := libgif-dev libwebp-dev libavcodec-dev libavformat-dev libavutil-dev \
                      libswscale-dev libx264-dev
CPFG_PACKAGES := libmcpp-dev
# GLB files: meshoptimizer's vertex orders and EXT_meshopt_compression codecs.
MESH_PACKAGES := libmeshoptimizer-dev
# Node.js and npm run the glTF validator in the tests; a machine that already has them
# (from any source) keeps its own, since Debian's npm conflicts with other Node builds.
NODE_PACKAGES := $(shell command -v node >/dev/null 2>&1 || echo nodejs) \
                 $(shell command -v npm >/dev/null 2>&1 || echo npm)
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
# graftal studio: its server is built on cpp-httplib; its browser tests drive Debian's
# chromium (the page's npm packages, playwright-core among them, come from
# studio/package-lock.json into $(BUILD_DIR)/studio-node when the build bundles the page).
STUDIO_PACKAGES := libcpp-httplib-dev chromium
# The Python module (docs/python.md): pybind11 against Debian's python3 and NumPy; its tests
# (pytest), the notebook they execute (nbclient, ipykernel), sweeps on Dask with pandas, and
# the examples' SciPy and Matplotlib.
PYTHON_PACKAGES := python3-dev python3-numpy pybind11-dev python3-pybind11 python3-pytest \
                   python3-nbclient python3-nbformat python3-ipykernel python3-pandas \
                   python3-dask python3-distributed python3-scipy python3-matplotlib

# The web build (docs/web.md): the engine in WebAssembly by Debian's emscripten, its npm
# package and the studio as a static page in $(BUILD_DIR)/web. Debian's emscripten tools need
# Debian's Node.js modules (acorn) on NODE_PATH, whichever node runs them.
WEB_PACKAGES := emscripten
WEB_BUILD_DIR ?= $(BUILD_DIR)/web-build
WEB_JOBS ?= 2
WEB_ENV := NODE_PATH=/usr/share/nodejs

# The fuzzing build: Debian's clang and its libFuzzer runtime (libclang-rt-dev depends on
# the default clang's libclang-rt-N-dev, which holds libclang_rt.fuzzer-x86_64.a). The whole
# library is compiled with the sanitizers, through this folder's CMAKE_CXX_FLAGS.
FUZZ_BUILD_DIR ?= build-fuzz
FUZZ_SECONDS ?= 300
FUZZ_TARGETS ?= parse derive surface expression data_files camera studio
FUZZ_PACKAGES := clang libclang-rt-dev
FUZZ_FLAGS := -fsanitize=address,undefined -fno-sanitize-recover=undefined \
              -fsanitize=fuzzer-no-link -fno-omit-frame-pointer -g

.PHONY: all deps configure build build-program test test-tools demo gallery bench clean fuzz-deps fuzz-build fuzz web-deps web bench-web

all: build

# Installs the Debian packages of $(1) that are missing.
define install-missing
@missing=""; for p in $(1); do \
  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
done; \
if [ -n "$$missing" ]; then \
  echo "installing:$$missing"; \
  $(SUDO) apt-get update -qq && \
  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing; \
fi
endef

deps:
	$(call install-missing,$(DEBIAN_PACKAGES) $(CPFG_PACKAGES) $(NODE_PACKAGES) $(MUSIC_PACKAGES) \
	  $(STUDIO_PACKAGES) $(ANIMATION_PACKAGES) $(MESH_PACKAGES) $(PYTHON_PACKAGES))

configure: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release > /dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

# Only what the gallery needs: the graftal program (with the studio's page), not the tests.
build-program: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target graftal

# The official glTF validator (npm) checks every .glb the tests write. It is a test tool,
# installed into the build folder, never into the repository.
test-tools: configure
	@if [ ! -d $(BUILD_DIR)/tools/node_modules/gltf-validator ]; then \
	  mkdir -p $(BUILD_DIR)/tools && \
	  npm install --silent --no-audit --no-fund --prefix $(BUILD_DIR)/tools gltf-validator@2.0.0-dev.3.10 > /dev/null; \
	fi

test: build test-tools web
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

web-deps:
	$(call install-missing,$(WEB_PACKAGES))

# The engine (only the sources it needs, ccache in front of em++), its npm package and the
# static page, all made by cmake/web.cmake into $(BUILD_DIR)/web.
web: web-deps
	@$(WEB_ENV) emcmake cmake -S . -B $(WEB_BUILD_DIR) -DGRAFTAL_WEB=ON -DCMAKE_BUILD_TYPE=Release \
	  -DGRAFTAL_WEB_OUTPUT=$(abspath $(BUILD_DIR))/web > /dev/null
	@$(WEB_ENV) cmake --build $(WEB_BUILD_DIR) -j $(WEB_JOBS)

demo: build-program
	@scripts/render_gallery.sh $(BUILD_DIR)/graftal gallery

gallery: demo

bench: build
	@bench/run.sh $(BUILD_DIR)

# The WebAssembly engine in Node.js beside the npm package lindenmayer (docs/web.md).
bench-web: web
	@node bench/web_bench.mjs $(BUILD_DIR)

fuzz-deps: deps
	$(call install-missing,$(FUZZ_PACKAGES))

# RelWithDebInfo at -O1 without NDEBUG: the library's assertions stay on while fuzzing.
# Static layers: a shared one is linked with --no-undefined, and the sanitizers' symbols
# come only with the fuzzer's executable.
fuzz-build: fuzz-deps
	@cmake -S . -B $(FUZZ_BUILD_DIR) -DCMAKE_CXX_COMPILER=clang++ -DGRAFTAL_FUZZ=ON \
	  -DGRAFTAL_BUILD_TESTS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBUILD_SHARED_LIBS=OFF \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_CXX_FLAGS="$(FUZZ_FLAGS)" > /dev/null
	@cmake --build $(FUZZ_BUILD_DIR) -j $(JOBS) --target graftal_fuzzers

# New corpus entries go to $(FUZZ_BUILD_DIR)/corpus/<target>, crashes, timeouts and
# out-of-memory inputs to $(FUZZ_BUILD_DIR)/findings/<target>; nothing is written into
# the repository.
fuzz: fuzz-build
	@fuzz/run_fuzzers.sh $(FUZZ_BUILD_DIR) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

clean:
	rm -rf $(BUILD_DIR)
