# The two commands of the README: `make demo` and `make test`. Each installs the Debian
# packages that are missing, configures, builds, and then renders the gallery or runs
# every test.

BUILD_DIR ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
DEBIAN_PACKAGES := cmake g++ make pkg-config ccache libgtest-dev libcli11-dev libcairo2-dev \
                   nlohmann-json3-dev poppler-utils libembree-dev libtinygltf-dev
# Node.js and npm run the glTF validator in the tests; a machine that already has them
# (from any source) keeps its own, since Debian's npm conflicts with other Node builds.
NODE_PACKAGES := $(shell command -v node >/dev/null 2>&1 || echo nodejs) \
                 $(shell command -v npm >/dev/null 2>&1 || echo npm)
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: all deps configure build test test-tools demo gallery bench clean

all: build

deps:
	@missing=""; for p in $(DEBIAN_PACKAGES) $(NODE_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing:$$missing"; \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing; \
	fi

configure: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release > /dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

# The official glTF validator (npm) checks every .glb the tests write. It is a test tool,
# installed into the build folder, never into the repository.
test-tools: configure
	@if [ ! -d $(BUILD_DIR)/tools/node_modules/gltf-validator ]; then \
	  mkdir -p $(BUILD_DIR)/tools && \
	  npm install --silent --no-audit --no-fund --prefix $(BUILD_DIR)/tools gltf-validator@2.0.0-dev.3.10 > /dev/null; \
	fi

test: build test-tools
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

demo: build
	@scripts/render_gallery.sh $(BUILD_DIR)/graftal gallery

gallery: demo

bench: build
	@bench/run.sh $(BUILD_DIR)

clean:
	rm -rf $(BUILD_DIR)
