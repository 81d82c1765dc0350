# parachute-fsi environment, like OpenFOAM's etc/bashrc. Source it from bash, do not run it:
#     . <build or install prefix>/share/fsi/fsi-env.sh
# It finds its own folder, so the build tree (build/share/fsi/) and any `cmake --install --prefix P`
# (P/share/fsi/) work alike, and sets:
#   PATH             += <root>/bin     the fsi command
#   LD_LIBRARY_PATH  += <root>/lib     libfsiFoam.so, which pimpleFoam loads by name (controlDict `libs`)
#   FSI_SHARE_DIR     = <root>/share/fsi   case-functions.sh, summarize.py and ramair_fluid.py (with its ramair_*.py parts), used by the cases' Allrun
#   WM_PROJECT_DIR    = /usr/share/openfoam unless already set (Debian's OpenFOAM v1912 finds its etc/ there)
# Sourcing it twice adds nothing twice.
if [ -z "${BASH_SOURCE:-}" ]; then
  echo "fsi-env.sh: source it from bash (. path/to/fsi-env.sh)" >&2
  return 2 2> /dev/null || exit 2
fi
_fsi_env_file=${BASH_SOURCE[0]}
FSI_SHARE_DIR=$(cd "$(dirname "$_fsi_env_file")" && pwd)
export FSI_SHARE_DIR
_fsi_root=$(cd "$FSI_SHARE_DIR/../.." && pwd)
case ":${PATH:-}:" in *":$_fsi_root/bin:"*) ;; *) export PATH="$_fsi_root/bin${PATH:+:$PATH}" ;; esac
case ":${LD_LIBRARY_PATH:-}:" in
  *":$_fsi_root/lib:"*) ;;
  *) export LD_LIBRARY_PATH="$_fsi_root/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" ;;
esac
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
unset _fsi_env_file _fsi_root
