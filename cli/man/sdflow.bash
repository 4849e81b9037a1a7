# Bash completion for sdflow: verbs, then the options of the verb typed, read from the program's
# own --help (so it follows every version), and file names elsewhere.
_sdflow() {
  local cur=${COMP_WORDS[COMP_CWORD]} verb="" i
  for ((i = 1; i < COMP_CWORD; ++i)); do
    case ${COMP_WORDS[i]} in
      -*) ;;
      *) verb=${COMP_WORDS[i]}; break ;;
    esac
  done
  local help words
  if [[ -z $verb ]]; then
    help=$("${COMP_WORDS[0]}" --help 2>/dev/null)
    if [[ $cur == -* ]]; then
      words=$(grep -oE -- '--?[A-Za-z][A-Za-z0-9-]*' <<< "$(sed -n '/^Options:/,/^Subcommands:/p' <<< "$help")")
    else
      words=$(awk '/^Subcommands:/ { on = 1; next } on && NF { print $1 }' <<< "$help")
    fi
    mapfile -t COMPREPLY < <(compgen -W "$words" -- "$cur")
    return
  fi
  if [[ $cur == -* ]]; then
    help=$("${COMP_WORDS[0]}" "$verb" --help 2>/dev/null)
    words=$(grep -oE -- '(^|[ ,])--?[A-Za-z][A-Za-z0-9-]*' <<< "$help" | tr -d ' ,' | sort -u)
    mapfile -t COMPREPLY < <(compgen -W "$words" -- "$cur")
    return
  fi
  mapfile -t COMPREPLY < <(compgen -f -- "$cur")
}
complete -o filenames -F _sdflow sdflow
