# Sourced by the scripts that make virtual environments of given CPython versions.
# pyenv_python 3.13: the newest of pyenv's CPython 3.13.x on this machine, else python3.13.
pyenv_python() {
  local found=""
  if command -v pyenv >/dev/null; then
    found=$(ls -d "$(pyenv root)/versions/$1".*/bin/python 2>/dev/null | sort -V | tail -n 1)
  fi
  echo "${found:-python$1}"
}
