# The two commands of the README, each doing all of its set-up on a fresh Debian 12 machine:
#   make demo   the paper's experiment on the default world: every method from every start room,
#               the tables in the terminal and everything in one page, build/demo/index.html
#   make test   build everything and run the whole test suite
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
BIMLOC := $(BUILD_DIR)/sim/bimloc
DEFAULT_WORLD := site_office
# The demo (docs/demo.md): the paper's method, its ablation and the two peers, every start room
# of the default world, two seeds each, on the same simulated scans; AMCL with its odometry
# noise set to the bench's, as the ROS amcl documentation advises (scenarios/configs/).
DEMO_METHODS := sgraph,pf-no-rooms,amcl,ndt
DEMO_CONFIG := scenarios/configs/amcl_legged.yaml
DEMO_SEEDS := 2
DEMO_DURATION_S := 60

# Every library comes from Debian (see docs/library.md: Dependencies); chromium is the browser the
# test of the demo's page opens it in (tests/test_compare_page.cpp).
DEB_PACKAGES := build-essential cmake pkg-config libifcplusplus-dev libboost-dev libeigen3-dev libassimp-dev \
                nlohmann-json3-dev libcli11-dev libgtest-dev libgmock-dev libembree-dev libbullet-dev \
                libyaml-cpp-dev libboost-filesystem-dev librosbag-storage-dev libsensor-msgs-dev \
                libnav-msgs-dev libtf2-msgs-dev pluginlib-dev librcpputils-dev libament-index-cpp-dev \
                python3-rosbag python3-numpy libpcl-dev libosmesa6-dev libpng-dev libceres-dev \
                libsqlite3-dev libzstd-dev liblz4-dev zlib1g-dev libisal-dev tcpdump \
                slurm-wlm munge chromium

.PHONY: all deps build test demo bench results worlds meshes clean

all: build

deps:
	@missing=""; for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing Debian packages:$$missing"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; \
	fi
	@# npm for the ROS 2 oracle test (tests/npm): Debian's package, unless a node.js that brings
	@# its own npm (NodeSource's, which conflicts with Debian's npm) is installed already.
	@command -v npm >/dev/null 2>&1 || { $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq npm; }

build: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo
	cmake --build $(BUILD_DIR) -j$(JOBS)

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS)

# An older demo's folder (plan/ and snapshots/, no compare.json) is build output: replaced.
demo: build
	@[ ! -e $(BUILD_DIR)/demo ] || [ -f $(BUILD_DIR)/demo/compare.json ] || rm -rf $(BUILD_DIR)/demo
	$(BIMLOC) compare --plan worlds/$(DEFAULT_WORLD).ifc --all-rooms --seeds $(DEMO_SEEDS) \
	  --methods $(DEMO_METHODS) --config $(DEMO_CONFIG) --duration $(DEMO_DURATION_S) --jobs $(JOBS) \
	  --out $(BUILD_DIR)/demo

bench: build
	$(BIMLOC) bench extract
	$(BIMLOC) bench lidar --plan worlds/$(DEFAULT_WORLD).ifc
	$(BIMLOC) bench simulate scenarios/site_office_R101.yaml
	$(BIMLOC) bench odometry
	$(BIMLOC) bench loop

# Rerun the fixed list of sweeps, compares and benchmarks (about 15 min on 2 cores) and regenerate
# the README's results table and docs/results/DATE.md (scripts/results.py). The shared plans are
# read from SHARED_IFC (rows needing them are skipped, with a note, when it is absent).
# RESULTS_ARGS: e.g. --quick (tiny cases), --only compare, --from-json build/results/json.
SHARED_IFC ?= ../shared/ifc
RESULTS_ARGS ?=
results: build
	python3 scripts/results.py --bimloc $(BIMLOC) --shared $(SHARED_IFC) $(RESULTS_ARGS)

# Regenerate the committed plans and meshes (tests check that they are up to date).
worlds: build
	$(BIMLOC) worldgen --all --out worlds

meshes: build
	for w in worlds/*.ifc; do n=$$(basename $$w .ifc); $(BIMLOC) extract $$w --out meshes/$$n; done

clean:
	rm -rf $(BUILD_DIR)
