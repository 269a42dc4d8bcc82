#!/usr/bin/env bash
# Build a trap-free XFOIL 6.99 from Debian's source package (bookworm: xfoil 6.99.dfsg+1-3),
# as used for tefcore/data/naca0012_flap35_xfoil.c81 (tools/make_xfoil_flap_deck.py).
#
# Why: Debian's binary (and upstream's Makefile) is built with the DEBUG flags
#   -fbounds-check -finit-real=inf -ffpe-trap=invalid,zero
# (bin/Makefile, CHK = ...; plotlib/config.make). With graphics switched off
# (PLOP / G F, needed without an X display) the first OPER point calls the Cp
# plot, whose GETWINSIZE (plotlib/plt_base.f:686) computes GX_SIZ / G_SCALE with
# G_SCALE = 0: 0/0 traps -> SIGFPE. With graphics on and no display XFOIL stops
# with "Cannot open display". The solver itself is unaffected (the viscous
# solution converges before the plot); removing the debug flags gives a binary
# whose results agree with the stock one (checked on NACA 0012, M 0.3, Re 1.8e6).
#
# Needs: deb-src for bookworm in the apt sources, gfortran, libx11-dev, make.
# Usage: tools/build_xfoil.sh [WORKDIR]   -> WORKDIR/xfoil-6.99.dfsg+1/bin/xfoil
set -euo pipefail
work=${1:-/tmp/xfoil-build}
mkdir -p "$work" && cd "$work"
apt-get source xfoil=6.99.dfsg+1-3
cd xfoil-6.99.dfsg+1
sed -i 's/^FFLAGS  += -fbounds-check -finit-real=inf -ffpe-trap=invalid,zero \$(DP)/FFLAGS  += $(DP)/' plotlib/config.make
sed -i 's/^CHK = -fbounds-check -finit-real=inf -ffpe-trap=invalid,zero -fallow-argument-mismatch/CHK = -fallow-argument-mismatch/' bin/Makefile
sed -i 's/-fbounds-check -finit-real=inf -ffpe-trap=invalid,zero //' orrs/bin/Makefile_DP
export FFLAGS="-O2" CFLAGS="-O2"
make -C orrs/bin -f Makefile_DP osgen
(cd orrs && bin/osgen osmaps_ns.lst)
make -C plotlib
make -C bin xfoil
echo "built $(pwd)/bin/xfoil"
