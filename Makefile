# ftsense: the two commands of the README.
#   make demo   install what is missing, build, run the main demo
#   make test   install what is missing, build, run every test
# Other targets: deps, build, docs (regenerate docs/config_reference.md, docs/ftsense-config.schema.json
# and the generated README blocks), sanitize, clean.

BUILD_DIR := build
JOBS ?= 2
# Debian packages the build needs (checked with dpkg; installed with apt-get when missing).
PACKAGES := cmake ninja-build g++ make pkg-config libeigen3-dev libceres-dev libboost-dev \
            nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev libmujoco-dev liburdfdom-dev python3 gnuplot-nox \
            pybind11-dev python3-dev python3-numpy python3-matplotlib python3-jsonschema

.PHONY: all deps configure build test demo docs sanitize clean

all: build

deps:
	@missing=""; \
	for p in $(PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "ftsense: installing Debian packages:$$missing"; \
	  SUDO=""; [ "$$(id -u)" -ne 0 ] && SUDO=sudo; \
	  $$SUDO apt-get update && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y --no-install-recommends $$missing; \
	fi

configure: deps
	cmake --preset default

build: configure
	cmake --build --preset default -j $(JOBS)

test: build
	ctest --preset default -j $(JOBS)

demo: build
	./$(BUILD_DIR)/bin/ftsense demo --output out/demo

docs: build
	bash tests/cli/check_generated_docs.sh ./$(BUILD_DIR)/bin/ftsense . --update

sanitize: deps
	cmake --preset sanitize
	cmake --build --preset sanitize -j $(JOBS)
	ctest --preset sanitize -j $(JOBS)

clean:
	rm -rf $(BUILD_DIR) build-sanitize
